#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "problems/scene_load_option_table.h"
#include "python/bindings.h"

namespace ipstep::python {
namespace {

// (nodes, dimension) array, a copy.
py::array_t<double> NodeArray(const std::vector<double>& values, int dimension) {
  const py::ssize_t nodes = static_cast<py::ssize_t>(values.size()) / dimension;
  py::array_t<double> array({nodes, static_cast<py::ssize_t>(dimension)});
  std::copy(values.begin(), values.end(), array.mutable_data());
  return array;
}

}  // namespace

std::shared_ptr<Scene> LoadSceneObject(const py::object& scene, const SceneLoadOptions& given) {
  SceneLoadOptions options = given;
  options.extra_effects = Effects().UserNames();
  if (py::isinstance<py::dict>(scene)) {
    const std::string text = py::module_::import("json").attr("dumps")(scene).cast<std::string>();
    return std::make_shared<Scene>(ParseScene(text, "<dict>", options));
  }
  const py::object fspath = py::module_::import("os").attr("fspath");
  std::string name;
  try {
    name = fspath(scene).cast<std::string>();
  } catch (const py::error_already_set&) {
    throw py::value_error("load_scene: expected a built-in scene name, a path or a dict, got " +
                          py::repr(scene).cast<std::string>());
  }
  py::gil_scoped_release release;  // meshing a solid can take seconds
  return std::make_shared<Scene>(LoadScene(name, options));
}

std::shared_ptr<const Scene> SceneArgument(const py::object& scene, py::dict* keywords) {
  SceneLoadOptions options;
  bool given = false;
  for (const auto& row : SceneLoadOptionTable()) {
    if (!keywords->contains(row.name)) continue;
    const py::object value = (*keywords)[py::str(row.name)];
    PyDict_DelItemString(keywords->ptr(), row.name.c_str());
    if (value.is_none()) continue;
    SetOption(row, ToOptionValue(row.field, value), &options);
    given = true;
  }
  if (py::isinstance<Scene>(scene)) {
    if (given) throw py::value_error("a loaded Scene takes no load_scene options (grid_size)");
    return scene.cast<std::shared_ptr<Scene>>();
  }
  return LoadSceneObject(scene, options);
}

void BindScenes(py::module_& m) {
  py::class_<Scene, std::shared_ptr<Scene>>(m, "Scene",
                                            "A scene: nodes, energies' data, run defaults "
                                            "(docs/scenes.md). Made by load_scene.")
      .def_readonly("name", &Scene::name)
      .def_readonly("source", &Scene::source)
      .def_readonly("dimension", &Scene::dimension)
      .def_readonly("time_step", &Scene::time_step, "the scene's time step [s]")
      .def_readonly("steps", &Scene::steps, "the scene's number of steps")
      .def_readonly("effects", &Scene::effects)
      .def_readonly("pinned", &Scene::pinned)
      .def_property_readonly("num_nodes", &Scene::num_nodes)
      .def_property_readonly(
          "positions", [](const Scene& s) { return NodeArray(s.positions, s.dimension); },
          "initial positions [m], (nodes, dimension), a copy")
      .def_property_readonly(
          "velocities", [](const Scene& s) { return NodeArray(s.velocities, s.dimension); },
          "initial velocities [m/s], (nodes, dimension), a copy")
      .def_property_readonly(
          "masses",
          [](const Scene& s) { return py::array_t<double>(s.masses.size(), s.masses.data()); },
          "node masses [kg], a copy")
      .def("__repr__", [](const Scene& s) {
        return "<ipstep.Scene " + s.name + ": " + std::to_string(s.num_nodes()) + " nodes, " +
               std::to_string(s.dimension) + "D>";
      });

  m.def(
      "load_scene",
      [](const py::object& scene, const py::kwargs& keywords) {
        SceneLoadOptions options;
        for (const auto& item : keywords) {
          const std::string name = item.first.cast<std::string>();
          const auto* row = FindOption(SceneLoadOptionTable(), name);
          if (row == nullptr) {
            throw py::value_error("load_scene: unknown option '" + name + "' (grid_size)");
          }
          if (item.second.is_none()) continue;
          SetOption(*row, ToOptionValue(row->field, item.second), &options);
        }
        return LoadSceneObject(scene, options);
      },
      py::arg("scene"),
      "load_scene(scene, grid_size=None): a built-in scene name (builtin_scenes()), a JSON "
      "file's path or a dict in the scene format (docs/scenes.md). Bad input raises ValueError "
      "naming the file (or '<dict>') and the key.");
  m.def(
      "builtin_scenes",
      [] {
        const std::set<std::string> names = BuiltinSceneNames();
        return std::vector<std::string>(names.begin(), names.end());
      },
      "The names of the built-in scenes, sorted.");
}

}  // namespace ipstep::python

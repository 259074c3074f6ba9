// The pieces of the Python module (module.cc), one concept per file.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>

#include "core/option_table.h"
#include "energies/effect_registry.h"
#include "problems/scene.h"
#include "problems/scene_loader.h"
#include "python/ipstep_module.h"
#include "sim/run_trajectory.h"
#include "sim/simulation.h"

namespace ipstep::python {

namespace py = pybind11;

// errors.cc: InputError -> ValueError (the message as the library words it),
// OutputError -> OSError.
void BindErrors(py::module_& m);

// registry.cc: Effects() (python/ipstep_module.h).

// scenes.cc: Scene, load_scene, builtin_scenes.
void BindScenes(py::module_& m);
// A scene loaded from a name, a path or a dict (with the registry's user effects).
std::shared_ptr<Scene> LoadSceneObject(const py::object& scene, const SceneLoadOptions& options);
// The argument `scene` of Simulation and compare: a Scene or what load_scene
// takes, loaded with the keywords of load_scene's options (grid_size), which
// are taken out of `keywords` (an error with a Scene already loaded).
std::shared_ptr<const Scene> SceneArgument(const py::object& scene, py::dict* keywords);

// options.cc: keyword options through the library's option tables
// (sim/simulation_option_table.h); an unknown keyword is a ValueError naming
// it (with a near miss).
SimulationOptions SimulationOptionsFrom(const py::dict& keywords);
// A Python bool, int, float or str as an option value; else ValueError naming `field`.
OptionValue ToOptionValue(const std::string& field, const py::handle& value);
RunOptions RunOptionsFrom(const py::dict& keywords);
void BindOptions(py::module_& m);

// simulation.cc: Simulation, StepReport, StepStatus, RunSummary.
void BindSimulation(py::module_& m);

// studies.cc: compare, bench.
void BindStudies(py::module_& m);

// python_energy.cc: register_energy.
void BindPythonEnergy(py::module_& m);
// Re-raises (and clears) the first exception a Python energy raised during the
// last step or run, if any. With the GIL.
void RaisePythonEnergyError();

}  // namespace ipstep::python

// `import ipstep`: the library from Python (docs/python.md).
#include "python/bindings.h"

PYBIND11_MODULE(ipstep, m) {
  m.doc() =
      "ipstep: every time step an optimisation problem, solved by Ceres (docs/python.md). "
      "load_scene, builtin_scenes, Simulation, compare, bench, register_energy.";
  namespace python = ipstep::python;
  python::BindErrors(m);
  python::BindScenes(m);
  python::BindOptions(m);
  python::BindSimulation(m);
  python::BindStudies(m);
  python::BindPythonEnergy(m);
}

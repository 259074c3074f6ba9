// `import ipstep`: the library from Python (docs/python.md).
#include <glog/logging.h>

#include "python/bindings.h"

PYBIND11_MODULE(ipstep, m) {
  m.doc() =
      "ipstep: every time step an optimisation problem, solved by Ceres (docs/python.md). "
      "load_scene, builtin_scenes, Simulation, compare, bench, register_energy.";
  namespace python = ipstep::python;
  // Quiet, as the programs are (apps/program_main.cc): nothing Ceres or glog
  // logs reaches a script (a step's status says what went wrong);
  // ipstep.set_log_level(0) brings the log back.
  FLAGS_logtostderr = true;
  FLAGS_minloglevel = google::GLOG_FATAL;
  if (!google::IsGoogleLoggingInitialized()) google::InitGoogleLogging("ipstep");
  m.def(
      "set_log_level", [](int level) { FLAGS_minloglevel = level; }, pybind11::arg("level"),
      "glog's minimum level of what Ceres and ipstep log to stderr: 0 info, 1 warnings, 2 "
      "errors, 3 (the default) nothing but fatal errors.");
  python::BindErrors(m);
  python::BindScenes(m);
  python::BindOptions(m);
  python::BindSimulation(m);
  python::BindStudies(m);
  python::BindPythonEnergy(m);
}

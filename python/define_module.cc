#include <glog/logging.h>

#include "python/bindings.h"

namespace ipstep::python {

void DefineModule(py::module_& m) {
  m.doc() =
      "ipstep: every time step an optimisation problem, solved by Ceres (docs/python.md). "
      "load_scene, builtin_scenes, Simulation, compare, bench, register_energy.";
  // Quiet, as the programs are (apps/program_main.cc): nothing Ceres or glog
  // logs reaches a script (a step's status says what went wrong);
  // set_log_level(0) brings the log back.
  FLAGS_logtostderr = true;
  FLAGS_minloglevel = google::GLOG_FATAL;
  if (!google::IsGoogleLoggingInitialized()) google::InitGoogleLogging("ipstep");
  m.def(
      "set_log_level", [](int level) { FLAGS_minloglevel = level; }, py::arg("level"),
      "glog's minimum level of what Ceres and ipstep log to stderr: 0 info, 1 warnings, 2 "
      "errors, 3 (the default) nothing but fatal errors.");
  BindErrors(m);
  BindScenes(m);
  BindOptions(m);
  BindSimulation(m);
  BindStudies(m);
  BindPythonEnergy(m);
}

}  // namespace ipstep::python

// Ctrl-C during a long call from Python (Simulation.run, compare, bench):
// the run loop reads a flag between steps (RunOptions::interrupt); after each
// step Check() takes the GIL for a moment and asks Python for pending signals
// (PyErr_CheckSignals). A KeyboardInterrupt (or whatever the handler raised)
// sets the flag: the step in progress finishes, the loop returns, and
// RaiseIfInterrupted() raises it once the GIL is back.
#pragma once

#include <csignal>
#include <memory>

#include <pybind11/pybind11.h>

namespace ipstep::python {

class PythonInterrupt {
 public:
  const volatile std::sig_atomic_t* flag() const { return &flag_; }
  // Without the GIL (it takes it). Also stops the loop on an error of an
  // after_step callback (Fail).
  void Check();
  // With the GIL: the exception of a Python callback; the loop stops after the step.
  void Fail(pybind11::error_already_set error);
  // With the GIL: raises what Check() or Fail() caught, if anything.
  void RaiseIfInterrupted();

 private:
  volatile std::sig_atomic_t flag_ = 0;
  std::unique_ptr<pybind11::error_already_set> error_;
};

}  // namespace ipstep::python

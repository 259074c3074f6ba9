#include "python/interrupt.h"

namespace ipstep::python {

namespace py = pybind11;

void PythonInterrupt::Check() {
  if (flag_ != 0) return;
  py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() != 0) Fail(py::error_already_set());
}

void PythonInterrupt::Fail(py::error_already_set error) {
  if (!error_) error_ = std::make_unique<py::error_already_set>(std::move(error));
  flag_ = 1;
}

void PythonInterrupt::RaiseIfInterrupted() {
  if (!error_) return;
  std::unique_ptr<py::error_already_set> error = std::move(error_);
  flag_ = 0;
  throw *error;
}

}  // namespace ipstep::python

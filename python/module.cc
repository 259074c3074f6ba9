// `import ipstep`: the library from Python (docs/python.md).
#include "python/ipstep_module.h"

PYBIND11_MODULE(ipstep, m) { ipstep::python::DefineModule(m); }

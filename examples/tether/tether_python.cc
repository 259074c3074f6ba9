// `import ipstep_tether`: everything `import ipstep` has, with the tether
// among the effects scenes may list.
//   PYTHONPATH=build-tether python3 -c "import ipstep_tether as ipstep; ..."
#include "python/ipstep_module.h"
#include "tether.h"

PYBIND11_MODULE(ipstep_tether, m) {
  ipstep::python::DefineModule(m);
  tether::RegisterTether(ipstep::python::Effects());
}

// The module's definition as a library call, for a module of one's own: an
// external project that registers C++ energies (examples/tether) builds its
// own module with them (docs/python.md, "C++ energies of your own"):
//
//   PYBIND11_MODULE(ipstep_tether, m) {
//     ipstep::python::DefineModule(m);
//     tether::RegisterTether(ipstep::python::Effects());
//   }
//
// Link the target ipstep::python (the installed package, with pybind11). One
// interpreter imports one such module: they register the same Python types.
#pragma once

#include <pybind11/pybind11.h>

#include "energies/effect_registry.h"

namespace ipstep::python {

// Defines everything `import ipstep` has (load_scene, Simulation, compare,
// bench, register_energy, ...) in `m`, and makes glog quiet (as the programs).
void DefineModule(pybind11::module_& m);

// The module's effect registry: a copy of the default effects
// (sim/default_effects.h) that register_energy, and a module of one's own,
// add to. Scenes are loaded and simulations built with it.
EffectRegistry& Effects();

}  // namespace ipstep::python

// The programs as library calls: a project that registers its own effects
// (docs/new_energy.md) and calls one of these from main() gets every flag,
// output and report of the ipstep programs for its scenes.
//
//   int main(int argc, char** argv) {
//     ipstep::EffectRegistry::Global().Register("tether", "...", BuildTether);
//     return ipstep::RunIpstep(argc, argv);
//   }
//
// Each parses and checks the command line (apps/program_main.h: one error line
// naming the flag or file and exit code 2 for bad input, --help, --version),
// runs and returns the exit code (0 success, 2 bad input, 3 a step failed with
// --on_failure=stop). Link ipstep::flags (installed with the library).
// Call one of them once per process: the flags are process-wide (gflags), so a
// second call starts from the values the first one parsed.
#pragma once

#include "energies/effect_registry.h"

namespace ipstep {

// ipstep: one scene with one integrator and one optimiser (README "The programs").
int RunIpstep(int argc, char** argv);
// ipstep_compare: every integrator x optimiser on one scene, as a table.
int RunCompare(int argc, char** argv);

// The same with the effects of `registry`: its user effects are accepted by the
// scene loader. The simulation builds effects from EffectRegistry::Global()
// today, so `registry` must be the global one until it takes a registry (a
// different one is refused with an internal error); the overloads above pass
// EffectRegistry::Global().
int RunIpstep(int argc, char** argv, const EffectRegistry& registry);
int RunCompare(int argc, char** argv, const EffectRegistry& registry);

}  // namespace ipstep

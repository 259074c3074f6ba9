// The programs as library calls: a project that registers its own effects
// (docs/new_energy.md) and calls one of these from main() gets every flag,
// output and report of the ipstep programs for its scenes.
//
//   int main(int argc, char** argv) {
//     ipstep::EffectRegistry effects = ipstep::MakeDefaultEffects();
//     effects.Register("tether", "...", BuildTether);
//     return ipstep::RunIpstep(argc, argv, effects);
//   }
//
// Each parses and checks the command line (apps/program_main.h: one error line
// naming the flag or file and exit code 2 for bad input, --help, --version),
// runs and returns the exit code (0 success, 2 bad input or an output path that
// cannot be written, 3 a step failed with --on_failure=stop or an output could
// not be written; RunIpstep: 130 / 143 interrupted by SIGINT / SIGTERM,
// apps/run_signals.h). Link ipstep::flags (installed with the library).
// Call one of them once per process: the flags are process-wide (gflags), so a
// second call starts from the values the first one parsed.
#pragma once

#include "energies/effect_registry.h"
#include "sim/default_effects.h"

namespace ipstep {

// ipstep: one scene with one integrator and one optimiser (docs/programs.md).
int RunIpstep(int argc, char** argv);
// ipstep_compare: every integrator x optimiser on one scene, as a table.
int RunCompare(int argc, char** argv);
// ipstep_tune: the cheapest configuration that reaches an error (apps/tune_program.cc).
// Its --shard, --merge and --reference_cache are also ipstep_bench's flags:
// call RunTune and RunBench (bench/bench_program.h) from different programs.
int RunTune(int argc, char** argv);

// The same with the effects of `registry` (the overloads above pass
// DefaultEffects(), sim/default_effects.h): scenes may list its effects and
// are built with them.
int RunIpstep(int argc, char** argv, const EffectRegistry& registry);
int RunCompare(int argc, char** argv, const EffectRegistry& registry);
int RunTune(int argc, char** argv, const EffectRegistry& registry);

}  // namespace ipstep

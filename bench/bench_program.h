// ipstep_bench as a library call (target ipstep::bench), like RunIpstep and
// RunCompare (apps/programs.h): a project that registers its own effects and
// calls RunBench from main() gets the whole sweep program (docs/benchmarks.md)
// for its scenes. Its flags --integrators and --optimizers share their names
// with ipstep_compare's, --shard, --merge and --reference_cache with
// ipstep_tune's: call RunBench and RunCompare or RunTune from different
// programs.
#pragma once

#include "energies/effect_registry.h"
#include "sim/default_effects.h"

namespace ipstep {

int RunBench(int argc, char** argv);
// Scenes may list the effects of `registry` and are built with them (the
// overload above: DefaultEffects(), sim/default_effects.h).
int RunBench(int argc, char** argv, const EffectRegistry& registry);

}  // namespace ipstep

// ipstep_bench with the tether: sweeps of integrator x optimiser x dt x
// tolerance into a CSV (docs/benchmarks.md).
//   tether_bench --scenes=tethered_square.json --optimizers=newton,lbfgs --output=sweep.csv
#include "bench/bench_program.h"
#include "tether.h"

int main(int argc, char** argv) {
  ipstep::EffectRegistry effects = ipstep::MakeDefaultEffects();
  tether::RegisterTether(effects);
  return ipstep::RunBench(argc, argv, effects);
}

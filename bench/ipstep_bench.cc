// ipstep_bench: sweeps scene x integrator x optimiser x dt x tolerance into a
// CSV (bench/bench_program.cc; docs/benchmarks.md).
#include "bench/bench_program.h"

int main(int argc, char** argv) { return ipstep::RunBench(argc, argv); }

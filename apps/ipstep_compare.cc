// ipstep_compare: every integrator x optimiser on one scene, as a table
// (apps/compare_program.cc; docs/programs.md "ipstep_compare").
#include "apps/programs.h"

int main(int argc, char** argv) { return ipstep::RunCompare(argc, argv); }

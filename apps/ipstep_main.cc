// ipstep: runs one scene with one integrator and one optimiser
// (apps/ipstep_program.cc; docs/programs.md "ipstep").
#include "apps/programs.h"

int main(int argc, char** argv) { return ipstep::RunIpstep(argc, argv); }

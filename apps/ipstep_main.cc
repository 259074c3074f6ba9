// ipstep: runs one scene with one integrator and one optimiser
// (apps/ipstep_program.cc; README "The programs").
#include "apps/programs.h"

int main(int argc, char** argv) { return ipstep::RunIpstep(argc, argv); }

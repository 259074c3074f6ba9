// ipstep_tune: the cheapest configuration that reaches an error
// (apps/tune_program.cc; docs/programs.md "ipstep_tune").
#include "apps/programs.h"

int main(int argc, char** argv) { return ipstep::RunTune(argc, argv); }

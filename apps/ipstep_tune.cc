// ipstep_tune: the cheapest configuration that reaches an error
// (apps/tune_program.cc; README "The programs").
#include "apps/programs.h"

int main(int argc, char** argv) { return ipstep::RunTune(argc, argv); }

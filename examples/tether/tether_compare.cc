// ipstep_compare with the tether: every integrator x optimiser on a scene.
//   tether_compare --scene=tethered_square.json
#include "apps/programs.h"
#include "tether.h"

int main(int argc, char** argv) {
  tether::RegisterTether(ipstep::EffectRegistry::Global());
  return ipstep::RunCompare(argc, argv);
}

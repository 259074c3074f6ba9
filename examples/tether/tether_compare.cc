// ipstep_compare with the tether: every integrator x optimiser on a scene.
//   tether_compare --scene=tethered_square.json
#include "apps/programs.h"
#include "tether.h"

int main(int argc, char** argv) {
  ipstep::EffectRegistry effects = ipstep::MakeDefaultEffects();
  tether::RegisterTether(effects);
  return ipstep::RunCompare(argc, argv, effects);
}

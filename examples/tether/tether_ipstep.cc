// The ipstep program with the tether: every flag (--help), CSV and frame
// output of ipstep, for scenes that use "tether".
//   tether_ipstep --scene=tethered_square.json --integrator=newmark --stats=stats.csv
#include "apps/programs.h"
#include "tether.h"

int main(int argc, char** argv) {
  ipstep::EffectRegistry effects = ipstep::MakeDefaultEffects();
  tether::RegisterTether(effects);
  return ipstep::RunIpstep(argc, argv, effects);
}

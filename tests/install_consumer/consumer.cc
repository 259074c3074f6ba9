// Uses the installed library: loads a built-in scene, takes ten steps.
#include <cstdio>

#include "problems/scene_loader.h"
#include "sim/simulation.h"

int main() {
  const ipstep::Scene scene = ipstep::LoadScene("oscillator");
  ipstep::SimulationOptions options;
  options.integrator.name = "newmark";
  ipstep::Simulation sim(scene, options);
  for (int i = 0; i < 10; ++i) {
    if (!sim.Step().converged) return 1;
  }
  std::printf("consumer: t = %g, E = %.6f\n", sim.state().time, sim.Energies().total());
  return 0;
}

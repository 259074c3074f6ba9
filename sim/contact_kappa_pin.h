// One barrier for every run of an accuracy comparison on a contact scene.
//
// Without a fixed contact.kappa the barrier stiffness adapts to the step
// (contact/adaptive_kappa.h: kappa_min ~ m / h^2, and the first contact's
// balance grows as h shrinks), so runs at different steps or error
// tolerances, and the reference they are measured against, simulate
// different barriers: on ball_drop_3d kappa spans 3e7 to 4e12 between them
// and the ball sinks 2-3 mm deeper into the d_hat = 1 cm layer in the softer
// ones, which is then counted as time-stepping error (docs/benchmarks.md
// "Contact accuracy: the barrier follows the step"). PinAdaptiveContactKappa
// takes the kappa one run settles on and fixes it for all of them.
#pragma once

#include "problems/scene.h"
#include "sim/simulation.h"

namespace ipstep {

// If `scene`, built with `options`, has contact whose kappa adapts, runs it
// with `options` (its integrator, optimiser, step and end) and sets
// options->effect_overrides["contact"]["kappa"] to the kappa the run ended
// with, which is returned. Returns 0 and leaves `options` as it is when the
// scene has no contact or its kappa is fixed already. Throws InputError for
// options the Simulation refuses; a run that fails or diverges still pins
// the kappa it reached.
double PinAdaptiveContactKappa(const Scene& scene, SimulationOptions* options);

}  // namespace ipstep

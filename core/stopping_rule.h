// The one stopping rule shared by every optimiser and integrator, in physical
// units. The gradient of the incremental potential divided by the potential
// weight is the force imbalance of the discrete equations of motion,
//   f = grad E / w_U   (newtons; for quasi-static, w_U = 1 and f = grad U - f_ext),
// and the measure is the velocity error that imbalance causes over one step:
//   residual = h * max_i |f_i| / m_i   [m/s]   over free nodes.
// A step has converged when residual <= tolerance. It is recomputed after
// every solve, whatever the optimiser reports.
#pragma once

#include <Eigen/Core>

#include "core/state.h"
#include "core/step_context.h"

namespace ipstep {

double StoppingMeasure(const Eigen::VectorXd& gradient, const State& state,
                       const StepContext& context);

}  // namespace ipstep

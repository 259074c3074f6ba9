// The optimiser items of ipstep_bench's --optimizers (and --reference_optimizer):
// an optimiser name (newton, dogleg, gauss_newton, lbfgs, ..., projected_newton,
// the Eigen reference of solver/projected_newton_solver.h) followed by options,
// or "none" (explicit integrators):
//   newton+sparse=SUITE_SPARSE+radius=1e8   lbfgs+rank=5   ncg+type=POLAK_RIBIERE
// Each key is short for an option of OptimizerOptions, whose row
// (solver/optimizer_option_table.h) gives its type, range and the optimisers
// it applies to, as for the ipstep flag of the same option:
//   sparse         sparse_library               threads  num_threads
//   radius         initial_trust_region_radius  rank     lbfgs_rank
//   backtrack      backtrack_rejected_steps     type     nonlinear_cg
//   linear_solver  linear_solver                line_search, max_iterations
//   ordering       linear_solver_ordering       projection  hessian_projection
// "none" takes no keys.
#pragma once

#include <string>

#include "solver/optimizer_options.h"

namespace ipstep {
namespace bench {

struct OptimizerSpec {
  std::string text;
  bool none = false;  // no optimiser (explicit integrator)
  OptimizerOptions options;
  bool projected_newton() const {
    return !none && options.optimizer == Optimizer::kProjectedNewton;
  }
};

// Parses and validates `text` (stopping tolerance `tolerance`). Throws
// InputError "optimizer spec: <text>: <key>: <why>".
OptimizerSpec ParseOptimizerSpec(const std::string& text, double tolerance);

}  // namespace bench
}  // namespace ipstep

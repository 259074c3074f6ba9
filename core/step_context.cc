#include "core/step_context.h"

namespace ipstep {

void StepContext::Resize(int dim, int num_nodes) {
  dimension = dim;
  const int n = dim * num_nodes;
  x_tilde.setZero(n);
  x_base.setZero(n);
  v_base.setZero(n);
  x_start.setZero(n);
}

}  // namespace ipstep

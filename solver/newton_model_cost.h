// How Ceres's trust region gets a projected Newton model without any change to
// Ceres (the newton and dogleg optimisers).
//
// Ceres builds its model from residual blocks as J^T J (Gauss-Newton). For a
// term with projected model Hessian H+ = V Lambda V^T (core/term_hessian.h;
// every eigenvalue > 0) and gradient g = V c, this cost function returns one
// residual per column of V,
//   r^ = Lambda^(-1/2) c,     J^ = Lambda^(1/2) V^T,
// and its companion loss (NewtonModelLoss) returns rho = [2 e, 1, 0], where e
// is the term's (weighted) energy, computed by the cost function in the same
// residual-block evaluation. Then for this block Ceres sees
//   cost       1/2 rho = e                       (the exact energy),
//   gradient   rho' J^T r^ = V Lambda^(1/2) Lambda^(-1/2) c = g,
//   model      rho' J^T J = V Lambda V^T = H+,
// For a full eigen-decomposition V is orthonormal and c = V^T g (one row per
// model coordinate); for a reduced model (an elastic element) V = B^T Q has
// one column per reduced coordinate (9 rows for a tetrahedron, not 12).
// and its corrector is the identity (rho' = 1, rho'' = 0). Levenberg-Marquardt
// and dogleg thereby become trust-region projected Newton, solved by Ceres's
// sparse Cholesky. Terms whose Gauss-Newton model is exact (inertia, affine
// residuals: Term::gauss_newton_model) stay ordinary residual blocks.
//
// Ceres calls a block's cost function and then its loss within one
// ResidualBlock::Evaluate, on one thread, so the energy handed from one to the
// other through the cost function is safe with num_threads > 1 (each block has
// its own pair; the scratch memory is thread-local). Evaluations without
// Jacobians (trial points) compute the energy only and set r^ = 0: Ceres takes
// their cost from the loss, which ignores its argument.
//
// Pair-difference terms (springs) have `dimension` residuals over d = x_1 - x_0:
// J^ is -S for x_0 and S for x_1, S = Lambda^(1/2) V^T, so J^T J is
// [[K+, -K+], [-K+, K+]] and the gradient [-g_d, g_d].
#pragma once

#include <ceres/cost_function.h>
#include <ceres/loss_function.h>

#include "core/term.h"
#include "core/term_hessian.h"

namespace ipstep {

class NewtonModelCache;

// The rows above from a term's model and its projection: residuals r^ (one
// per column of V) and per parameter block b the row-major rows x dimension
// Jacobian block jacobians[b] (null blocks are skipped).
void NewtonModelRows(const Term& term, int dimension, const ProjectedHessian& projected,
                     double* residuals, double** jacobians);

class NewtonModelCost : public ceres::CostFunction {
 public:
  // `weight` (the family's step weight), `veto` (a step filter refused the
  // trial point: evaluation fails) and `filter` (may be null: clamp) are read
  // at every evaluation. With a `cache` (solver/newton_model_cache.h) holding
  // the point, its k-th entry `cache_index` is copied instead of computed.
  NewtonModelCost(const Term* term, int dimension, const double* weight, const bool* veto,
                  const EigenvalueFilter* filter = nullptr, const NewtonModelCache* cache = nullptr,
                  int cache_index = -1);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;
  // The weighted energy of the last evaluation.
  double energy() const { return energy_; }

 private:
  const Term* term_;
  int dimension_;
  const double* weight_;
  const bool* veto_;
  const EigenvalueFilter* filter_;
  const NewtonModelCache* cache_;
  int cache_index_;
  mutable double energy_ = 0.0;
};

// rho(s) = 2 e (the energy its cost function just computed), rho' = 1, rho'' = 0.
class NewtonModelLoss : public ceres::LossFunction {
 public:
  explicit NewtonModelLoss(const NewtonModelCost* cost) : cost_(cost) {}
  void Evaluate(double s, double rho[3]) const override;

 private:
  const NewtonModelCost* cost_;
};

}  // namespace ipstep

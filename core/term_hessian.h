// The second-order model of one energy term: its value, gradient and exact
// Hessian at x, and the Hessian projected to the positive semi-definite cone.
// Shared by every Newton method: the Ceres trust region (through
// solver/newton_model_cost.h) and the Eigen projected Newton
// (solver/projected_newton_solver.h) build their models from it.
//
// For a term e = w/2 rho(|r|^2) with residuals r(x), Jacobian J, loss rho
// (rho(s) = s without a loss) and family weight w:
//   grad e = w rho' J^T r
//   Hess e = w (rho' J^T J + 2 rho'' (J^T r)(J^T r)^T + rho' sum_k r_k Hess(r_k)).
// Gauss-Newton (Ceres's own model) keeps the first two parts. The last one
// comes from the term's analytic ResidualCurvature (core/term.h) when it has
// one, otherwise from central differences of its own Jacobian with r fixed:
//   column j = (J(x + delta e_j) - J(x - delta e_j))^T r / (2 delta),
//   delta = kCurvatureStep max(1, |x_j|),
// symmetrised: O(delta^2) accurate (about 1e-8 relative for analytic or autodiff
// Jacobians). The gradient stays exact, so the point a Newton method converges
// to is exact; only the rate depends on the curvature. A term that cannot be
// evaluated beside x (a barrier at the edge of its domain) keeps its
// Gauss-Newton part, which is PSD. Terms with Term::gauss_newton_model skip
// the last part (their residuals are affine, or they chose Gauss-Newton).
//
// Model coordinates: the term's parameters (nodes x dimension), or for
// pair-difference terms (Term::pair_difference) d = x_1 - x_0, in which the
// gradient is de/dx_1 (= -de/dx_0) and the Hessian is K with
// Hess e = [[K, -K], [-K, K]]. K's eigenvalues are half of the full matrix's
// on the modes x_1 - x_0 (the translations have eigenvalue 0), so projecting K
// projects the full Hessian.
//
// Projection (ProjectHessian): H = V diag(lambda) V^T, each eigenvalue
// filtered and then raised to at least kCurvatureFloor * s, where
// s = max(max_i |lambda_i|, w rho' |J|_F^2) is the term's curvature scale. The
// filters:
//  * clamp (EigenvalueFilter::kClamp): negative curvature becomes a tiny
//    positive one (the textbook's clamp to zero, up to 1e-8 s);
//  * absolute (kAbsolute): lambda -> |lambda| (Chen, Liu, Levin, Zheng,
//    Jacobson 2024, "Stabler Neo-Hookean Simulation: Absolute Eigenvalue
//    Filtering for Projected Newton"): a mode of negative curvature keeps its
//    magnitude, so the model does not call it free; a larger model curvature
//    than clamping gives, i.e. a shorter, more cautious step along it.
// Either way every mode the gradient has is also a mode of the model: Ceres's
// representation of the model (solver/newton_model_cost.h) needs positive
// eigenvalues. s = 0 only for a term with J = 0 and H = 0, whose gradient is
// zero too.
//
// Reduced models (Term::reduced_model): terms whose energy is a function of
// reduced coordinates y = B x (k of them; an elastic element's deformation
// gradient, k = d^2 < n = (d + 1) d) give the energy e, its gradient p in y
// and the eigensystem A = Q diag(l) Q^T of its Hessian in y in closed form.
// Then grad e = B^T p, Hess e = B^T A B, and the projection filters the
// eigenvalues l of A: H+ = (B^T Q) diag(f(l)) (B^T Q)^T, which is positive
// semi-definite with B^T A B = Hess e wherever A is positive definite (the
// projection in the space of F, Teran et al. 2005; Smith, de Goes, Kim 2019).
// So a projected model needs no n x n eigen-decomposition, and its Ceres
// representation has k rows, not n.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/term.h"

namespace ipstep {

using TermMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxTermCoordinates,
                                 kMaxTermCoordinates>;
using TermVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxTermCoordinates, 1>;

constexpr double kCurvatureStep = 1e-6;
constexpr double kCurvatureFloor = 1e-8;
// The most reduced coordinates a ReducedModel may have.
constexpr int kMaxReducedCoordinates = 9;

enum class EigenvalueFilter { kClamp, kAbsolute };

// Model coordinates of a term: dimension for pair-difference terms, else
// nodes x dimension.
int ModelSize(const Term& term, int dimension);

using ReducedMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0,
                                    kMaxReducedCoordinates, kMaxReducedCoordinates>;
using ReducedVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxReducedCoordinates, 1>;
using ReducedMap = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxReducedCoordinates,
                                 kMaxTermCoordinates>;

// What Term::reduced_model fills (unweighted), in coordinates y = B x.
struct ReducedModel {
  double energy = 0.0;
  ReducedVector gradient;      // de/dy (k)
  ReducedVector eigenvalues;   // of A = d2e/dy2 (k), any order
  ReducedMatrix eigenvectors;  // k x k, orthonormal columns: A = Q diag(l) Q^T
  ReducedMap map;              // B: k x n (n = the term's nodes x dimension)
};

struct TermModel {
  double energy = 0.0;              // weighted
  TermVector gradient;              // weighted, over the model coordinates
  TermMatrix hessian;               // weighted, exact (Gauss-Newton for gauss_newton_model terms)
  double gauss_newton_scale = 0.0;  // w rho' |J|_F^2 (over the model coordinates)
  bool curvature_dropped = false;   // finite differences left the term's domain
  // Terms with a reduced model: the weighted eigensystem of the Hessian in y,
  // as directions in x (columns B^T Q_k, n x k), eigenvalues (weighted l) and
  // the gradient's coordinates Q^T p (weighted): gradient = directions *
  // coordinates, hessian = directions diag(values) directions^T.
  bool reduced = false;
  TermMatrix reduced_directions;
  TermVector reduced_values;
  TermVector reduced_coordinates;
};

// H+ = vectors diag(values) vectors^T, every value > 0 unless H = 0 and J = 0,
// and the gradient g = vectors * coordinates. vectors: n x m, m <= n; for a
// full eigen-decomposition orthonormal (m = n, coordinates = V^T g), for a
// reduced model the directions B^T Q (m = k).
struct ProjectedHessian {
  TermMatrix vectors;
  TermVector values;
  TermVector coordinates;
};

// Evaluates term models; holds the scratch memory (one per thread).
class TermModelEvaluator {
 public:
  // x: the term's parameter blocks (one per node). Energy only when `hessian`
  // is false (then gradient and hessian are left alone). False if the term
  // cannot be evaluated at x or the result is not finite.
  bool Evaluate(const Term& term, int dimension, double weight, const double* const* x,
                bool hessian, TermModel* model);

 private:
  // Residuals and the column-major m x n model Jacobian into `jacobian`
  // (resized to hold it; any residual count m).
  bool EvaluateJacobian(const Term& term, int dimension, bool pair, double* residuals,
                        std::vector<double>* jacobian);

  std::vector<double> local_x_;
  std::vector<const double*> parameters_;
  std::vector<double> residuals_;
  std::vector<double> residuals_fd_;
  std::vector<double> jacobian_blocks_;
  std::vector<double*> jacobian_pointers_;
  Eigen::Map<const Eigen::MatrixXd> FdJacobian(int m, int n) const {
    return Eigen::Map<const Eigen::MatrixXd>(jacobian_fd_.data(), m, n);
  }

  bool EvaluateEnergy(const Term& term, double weight, const double* const* x, TermModel* model);
  bool EvaluateReduced(const Term& term, int dimension, double weight, const double* const* x,
                       TermModel* model);

  std::vector<double> jacobian_;
  std::vector<double> jacobian_fd_;
  TermMatrix curvature_;
  TermVector column_;
  ReducedModel reduced_;
  TermMatrix scaled_;
};

// Eigen-decomposition of a symmetric term matrix, ascending eigenvalues
// (Eigen's fixed-size solvers for the common sizes, closed form up to 3).
void DecomposeSymmetric(const TermMatrix& m, TermVector* values, TermMatrix* vectors);

// The rows of a term's Newton model in Ceres (solver/newton_model_cost.h): k
// for a reduced model, else ModelSize.
int ModelRows(const Term& term, int dimension);

// Eigen-decomposition of the symmetric model Hessian (fixed-size solvers for
// the common sizes, closed form up to 3; a reduced model's own eigensystem),
// filtered, with the eigenvalue floor above.
void ProjectHessian(const TermModel& model, ProjectedHessian* projected,
                    EigenvalueFilter filter = EigenvalueFilter::kClamp);

}  // namespace ipstep

#include "core/term_hessian.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace ipstep {
namespace {

template <int N>
void DecomposeFixed(const TermMatrix& h, TermVector* values, TermMatrix* vectors) {
  using Fixed = Eigen::Matrix<double, N, N>;
  Eigen::SelfAdjointEigenSolver<Fixed> eigen;
  if constexpr (N <= 3) {
    eigen.computeDirect(h.template topLeftCorner<N, N>());
  } else {
    eigen.compute(h.template topLeftCorner<N, N>());
  }
  *vectors = eigen.eigenvectors();
  *values = eigen.eigenvalues();
}

}  // namespace

void DecomposeSymmetric(const TermMatrix& m, TermVector* values, TermMatrix* vectors) {
  switch (m.rows()) {
    case 1:
      vectors->setOnes(1, 1);
      values->setConstant(1, m(0, 0));
      return;
    case 2:
      return DecomposeFixed<2>(m, values, vectors);
    case 3:
      return DecomposeFixed<3>(m, values, vectors);
    case 4:
      return DecomposeFixed<4>(m, values, vectors);
    case 6:
      return DecomposeFixed<6>(m, values, vectors);
    case 9:
      return DecomposeFixed<9>(m, values, vectors);
    case 12:
      return DecomposeFixed<12>(m, values, vectors);
    default: {
      Eigen::SelfAdjointEigenSolver<TermMatrix> eigen(m);
      *vectors = eigen.eigenvectors();
      *values = eigen.eigenvalues();
    }
  }
}

int ModelSize(const Term& term, int dimension) {
  return term.pair_difference ? dimension : dimension * static_cast<int>(term.nodes.size());
}

int ModelRows(const Term& term, int dimension) {
  return term.reduced_model ? term.reduced_size : ModelSize(term, dimension);
}

bool TermModelEvaluator::EvaluateEnergy(const Term& term, double weight, const double* const* x,
                                        TermModel* model) {
  const int m = term.cost->num_residuals();
  if (static_cast<int>(residuals_.size()) < m) {
    residuals_.resize(m);
    residuals_fd_.resize(m);
  }
  if (!term.cost->Evaluate(x, residuals_.data(), nullptr)) return false;
  double s = 0.0;
  for (int r = 0; r < m; ++r) s += residuals_[r] * residuals_[r];
  double rho[3] = {s, 1.0, 0.0};
  if (term.loss) term.loss->Evaluate(s, rho);
  model->energy = 0.5 * weight * rho[0];
  return std::isfinite(model->energy);
}

bool TermModelEvaluator::EvaluateReduced(const Term& term, int dimension, double weight,
                                         const double* const* x, TermModel* model) {
  // The energy as the term defines it (cost and loss), so that trial points
  // (energy only) and models compare the same numbers.
  if (!EvaluateEnergy(term, weight, x, model)) return false;
  if (!term.reduced_model(x, true, &reduced_)) return false;
  const int n = dimension * static_cast<int>(term.nodes.size());
  model->gradient.noalias() = weight * (reduced_.map.transpose() * reduced_.gradient);
  model->reduced = true;
  model->curvature_dropped = false;
  model->gauss_newton_scale = 0.0;
  // Directions B^T Q (n x k): the Hessian is directions diag(w l) directions^T.
  model->reduced_directions.noalias() = reduced_.map.transpose() * reduced_.eigenvectors;
  model->reduced_values = weight * reduced_.eigenvalues;
  model->reduced_coordinates.noalias() =
      weight * (reduced_.eigenvectors.transpose() * reduced_.gradient);
  scaled_.noalias() = model->reduced_directions * model->reduced_values.asDiagonal();
  model->hessian.resize(n, n);
  model->hessian.noalias() = scaled_ * model->reduced_directions.transpose();
  return model->gradient.allFinite() && model->hessian.allFinite();
}

bool TermModelEvaluator::EvaluateJacobian(const Term& term, int dimension, bool pair,
                                          double* residuals, std::vector<double>* jacobian) {
  const int blocks = static_cast<int>(term.nodes.size());
  const int m = term.cost->num_residuals();
  for (int b = 0; b < blocks; ++b) {
    // A pair-difference term needs dr/dx_1 = dr/dd only.
    jacobian_pointers_[b] =
        pair && b == 0 ? nullptr : jacobian_blocks_.data() + static_cast<size_t>(b) * m * dimension;
  }
  if (!term.cost->Evaluate(parameters_.data(), residuals, jacobian_pointers_.data())) return false;
  // Row-major m x dimension blocks into the column-major m x n model Jacobian.
  const int first = pair ? 1 : 0;
  jacobian->resize(static_cast<size_t>(m) * dimension * (blocks - first));
  for (int b = first; b < blocks; ++b) {
    const double* block = jacobian_pointers_[b];
    for (int r = 0; r < m; ++r) {
      for (int k = 0; k < dimension; ++k) {
        (*jacobian)[static_cast<size_t>((b - first) * dimension + k) * m + r] =
            block[r * dimension + k];
      }
    }
  }
  return true;
}

bool TermModelEvaluator::Evaluate(const Term& term, int dimension, double weight,
                                  const double* const* x, bool hessian, TermModel* model) {
  model->reduced = false;
  if (!hessian) return EvaluateEnergy(term, weight, x, model);
  if (term.reduced_model) return EvaluateReduced(term, dimension, weight, x, model);
  const int blocks = static_cast<int>(term.nodes.size());
  const int m = term.cost->num_residuals();
  if (static_cast<int>(residuals_.size()) < m) {
    residuals_.resize(m);
    residuals_fd_.resize(m);
  }
  // Local copies of the parameters: finite differences perturb them.
  const int nt = dimension * blocks;
  if (static_cast<int>(jacobian_blocks_.size()) < m * nt) jacobian_blocks_.resize(m * nt);
  local_x_.resize(nt);
  parameters_.resize(blocks);
  jacobian_pointers_.resize(blocks);
  for (int b = 0; b < blocks; ++b) {
    std::copy(x[b], x[b] + dimension, local_x_.begin() + b * dimension);
    parameters_[b] = local_x_.data() + b * dimension;
  }
  const bool pair = term.pair_difference;
  if (!EvaluateJacobian(term, dimension, pair, residuals_.data(), &jacobian_)) return false;
  const int n = pair ? dimension : nt;
  const Eigen::Map<const Eigen::MatrixXd> jacobian(jacobian_.data(), m, n);
  const Eigen::Map<const Eigen::VectorXd> r(residuals_.data(), m);
  const double s = r.squaredNorm();
  double rho[3] = {s, 1.0, 0.0};
  if (term.loss) term.loss->Evaluate(s, rho);
  model->energy = 0.5 * weight * rho[0];
  const TermVector jtr = jacobian.transpose() * r;
  model->gradient = (weight * rho[1]) * jtr;
  model->hessian.noalias() = (weight * rho[1]) * jacobian.transpose() * jacobian;
  // Ceres's corrector keeps the rho'' part only where it is positive (else it
  // scales J by sqrt(rho')); a Gauss-Newton model is Ceres's model.
  const double rho2 = term.gauss_newton_model ? std::max(rho[2], 0.0) : rho[2];
  model->hessian.noalias() += (2.0 * weight * rho2) * jtr * jtr.transpose();
  model->gauss_newton_scale = weight * rho[1] * jacobian.squaredNorm();
  model->curvature_dropped = false;
  if (!term.gauss_newton_model && rho[1] != 0.0 && weight != 0.0) {
    curvature_.resize(n, n);
    bool ok = true;
    if (term.curvature) {
      ok = term.curvature(parameters_.data(), residuals_.data(), curvature_.data());
      // The callback writes row-major; the matrix is symmetric up to round-off.
    } else {
      // Columns over the model coordinates: for a pair-difference term d moves
      // with x_1 (x_0 fixed).
      const int offset = pair ? dimension : 0;
      for (int j = 0; j < n && ok; ++j) {
        double& coordinate = local_x_[offset + j];
        const double saved = coordinate;
        const double step = kCurvatureStep * std::max(1.0, std::abs(saved));
        coordinate = saved + step;
        const double up = coordinate;
        ok = EvaluateJacobian(term, dimension, pair, residuals_fd_.data(), &jacobian_fd_);
        if (ok) column_.noalias() = FdJacobian(m, n).transpose() * r;
        coordinate = saved - step;
        const double down = coordinate;
        ok = ok && EvaluateJacobian(term, dimension, pair, residuals_fd_.data(), &jacobian_fd_);
        if (ok) curvature_.col(j) = (column_ - FdJacobian(m, n).transpose() * r) / (up - down);
        coordinate = saved;
      }
    }
    if (ok && curvature_.allFinite()) {
      model->hessian += (0.5 * weight * rho[1]) * (curvature_ + curvature_.transpose());
    } else {
      model->curvature_dropped = true;
    }
  }
  return std::isfinite(model->energy) && model->gradient.allFinite() && model->hessian.allFinite();
}

void ProjectHessian(const TermModel& model, ProjectedHessian* projected, EigenvalueFilter filter) {
  if (model.reduced) {
    projected->vectors = model.reduced_directions;
    projected->values = model.reduced_values;
    projected->coordinates = model.reduced_coordinates;
  } else {
    DecomposeSymmetric(model.hessian, &projected->values, &projected->vectors);
    projected->coordinates.resize(projected->vectors.cols());
    for (int i = 0; i < projected->vectors.cols(); ++i) {
      projected->coordinates[i] = projected->vectors.col(i).dot(model.gradient);
    }
  }
  const double scale =
      std::max(projected->values.size() > 0 ? projected->values.cwiseAbs().maxCoeff() : 0.0,
               model.gauss_newton_scale);
  if (filter == EigenvalueFilter::kAbsolute) projected->values = projected->values.cwiseAbs();
  projected->values = projected->values.cwiseMax(kCurvatureFloor * scale);
}

}  // namespace ipstep

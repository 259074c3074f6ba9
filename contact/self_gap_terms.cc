#include "contact/self_gap_terms.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>

#include "contact/barrier.h"
#include "contact/distance_hessian.h"
#include "contact/friction.h"
#include "geometry/edge_edge_mollifier.h"
#include "geometry/point_triangle.h"
#include "geometry/segment_segment.h"

namespace ipstep {

namespace {

using Vector12 = Eigen::Matrix<double, 12, 1>;

Eigen::Vector3d Block(const double* const* x, int k) {
  return Eigen::Vector3d(x[k][0], x[k][1], x[k][2]);
}

// Residual u and Jacobian blocks -grad d_eff (grad: 12 coordinates).
void WriteResidual(double u, const Vector12& grad, double* residuals, double** jacobians) {
  residuals[0] = u;
  if (jacobians == nullptr) return;
  for (int block = 0; block < 4; ++block) {
    if (jacobians[block] == nullptr) continue;
    for (int k = 0; k < 3; ++k) jacobians[block][k] = u > 0.0 ? -grad[3 * block + k] : 0.0;
  }
}

}  // namespace

PointTriangleGap::PointTriangleGap(double d_hat, double min_distance)
    : d_hat_(d_hat), min_distance_(min_distance) {
  set_num_residuals(1);
  for (int b = 0; b < 4; ++b) mutable_parameter_block_sizes()->push_back(3);
}

bool PointTriangleGap::Evaluate(double const* const* x, double* residuals,
                                double** jacobians) const {
  const PointTriangleDistanceResult r =
      PointTriangleDistance(Block(x, 0), Block(x, 1), Block(x, 2), Block(x, 3));
  if (!(r.distance > min_distance_)) return false;
  Vector12 grad;
  grad << r.grad_p, r.grad_a, r.grad_b, r.grad_c;
  WriteResidual(std::max(d_hat_ - r.distance, 0.0), grad, residuals, jacobians);
  return true;
}

bool PointTriangleGap::Curvature(const double* const* x, const double* c, double* curvature) const {
  const Eigen::Vector3d p = Block(x, 0), a = Block(x, 1), b = Block(x, 2), v = Block(x, 3);
  const double d = PointTriangleDistance(p, a, b, v).distance;
  if (!(d > min_distance_)) return false;
  Eigen::Map<Eigen::Matrix<double, 12, 12, Eigen::RowMajor>> out(curvature);
  if (!(d < d_hat_)) {
    out.setZero();
    return true;
  }
  Matrix12d hessian;
  if (!PointTriangleDistanceHessian(p, a, b, v, &hessian)) return false;
  out = -c[0] * hessian;
  return true;
}

double InverseBarrierGap(double beta, double d_hat, double u_max) {
  if (!(beta > 0.0)) return 0.0;
  // g(u) = B(d_hat - u) - beta: increasing and convex on (0, d_hat), g(u_max)
  // >= 0, so Newton from u_max decreases monotonically to the root.
  double u = u_max;
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double d = d_hat - u;
    const double g = Barrier(d, d_hat) - beta;
    const double slope = -BarrierDerivative(d, d_hat);  // dB(d_hat - u)/du
    if (!(g > 0.0) || !(slope > 0.0)) break;
    const double next = u - g / slope;
    if (!(next < u)) break;
    if (u - next <= 1e-16 * u) {
      u = std::max(next, 0.0);
      break;
    }
    u = std::max(next, 0.0);
  }
  return u;
}

EdgeEdgeGap::EdgeEdgeGap(double d_hat, double min_distance, double eps_x)
    : d_hat_(d_hat), min_distance_(min_distance), eps_x_(eps_x) {
  set_num_residuals(1);
  for (int b = 0; b < 4; ++b) mutable_parameter_block_sizes()->push_back(3);
}

bool EdgeEdgeGap::EffectiveDistance(const double* const* x, double* d_m, double* gradient,
                                    double* hessian) const {
  const Eigen::Vector3d a0 = Block(x, 0), a1 = Block(x, 1), b0 = Block(x, 2), b1 = Block(x, 3);
  const SegmentSegmentDistanceResult r = SegmentSegmentDistance(a0, a1, b0, b1);
  const double d = r.distance;
  if (!(d > min_distance_)) return false;
  if (!(d < d_hat_)) {
    *d_m = d_hat_;
    if (gradient != nullptr) Eigen::Map<Vector12>{gradient}.setZero();
    if (hessian != nullptr) Eigen::Map<Matrix12d>{hessian}.setZero();
    return true;
  }
  Vector12 grad_d;
  grad_d << r.grad_a0, r.grad_a1, r.grad_b0, r.grad_b1;
  const EdgeEdgeMollifier m = EdgeEdgeMollify(
      a0, a1, b0, b1, eps_x_, gradient != nullptr || hessian != nullptr, hessian != nullptr);
  if (!m.active()) {
    *d_m = d;
    if (gradient != nullptr) Eigen::Map<Vector12>{gradient} = grad_d;
    if (hessian != nullptr) {
      Matrix12d h;
      if (!EdgeEdgeDistanceHessian(a0, a1, b0, b1, &h)) return false;
      Eigen::Map<Matrix12d>{hessian} = h;
    }
    return true;
  }
  const double b = Barrier(d, d_hat_), b1d = BarrierDerivative(d, d_hat_);
  const double beta = m.value * b;
  const double u = InverseBarrierGap(beta, d_hat_, d_hat_ - d);
  *d_m = d_hat_ - u;
  const double slope = BarrierDerivative(*d_m, d_hat_);  // B'(d_m) < 0 unless u = 0
  const bool flat = !(slope < 0.0);
  const Vector12 grad_beta = b * m.gradient + (m.value * b1d) * grad_d;
  const Vector12 grad_dm = flat ? Vector12::Zero() : Vector12(grad_beta / slope);
  if (gradient != nullptr) Eigen::Map<Vector12>{gradient} = grad_dm;
  if (hessian != nullptr) {
    Eigen::Map<Matrix12d> out(hessian);
    if (flat) {
      out.setZero();
      return true;
    }
    Matrix12d hess_d;
    if (!EdgeEdgeDistanceHessian(a0, a1, b0, b1, &hess_d)) return false;
    const double b2d = BarrierSecondDerivative(d, d_hat_);
    Matrix12d hess_beta =
        b * m.hessian + b1d * (m.gradient * grad_d.transpose() + grad_d * m.gradient.transpose()) +
        m.value * (b2d * grad_d * grad_d.transpose() + b1d * hess_d);
    out =
        (hess_beta - BarrierSecondDerivative(*d_m, d_hat_) * grad_dm * grad_dm.transpose()) / slope;
  }
  return true;
}

bool EdgeEdgeGap::Evaluate(double const* const* x, double* residuals, double** jacobians) const {
  double d_m = 0.0;
  Vector12 grad;
  if (!EffectiveDistance(x, &d_m, jacobians != nullptr ? grad.data() : nullptr, nullptr)) {
    return false;
  }
  if (jacobians == nullptr) grad.setZero();
  WriteResidual(std::max(d_hat_ - d_m, 0.0), grad, residuals, jacobians);
  return true;
}

bool EdgeEdgeGap::Curvature(const double* const* x, const double* c, double* curvature) const {
  double d_m = 0.0;
  Matrix12d hessian;
  if (!EffectiveDistance(x, &d_m, nullptr, hessian.data())) return false;
  // Symmetric: row- and column-major agree.
  Eigen::Map<Matrix12d> out(curvature);
  if (d_m < d_hat_) {
    out = -c[0] * hessian;
  } else {
    out.setZero();
  }
  return true;
}

SelfFriction::SelfFriction(const StepContext* context, const int nodes[4], const double alpha[4],
                           const Eigen::Matrix<double, 3, 2>& tangents, double eps_v)
    : context_(context), tangents_(tangents), eps_v_(eps_v) {
  for (int k = 0; k < 4; ++k) {
    nodes_[k] = nodes[k];
    alpha_[k] = alpha[k];
  }
  set_num_residuals(2);
  for (int b = 0; b < 4; ++b) mutable_parameter_block_sizes()->push_back(3);
}

bool SelfFriction::Evaluate(double const* const* x, double* residuals, double** jacobians) const {
  Eigen::Vector3d v_rel = Eigen::Vector3d::Zero();
  for (int k = 0; k < 4; ++k) {
    double v[3];
    context_->Velocity(nodes_[k], x[k], v);
    v_rel += alpha_[k] * Eigen::Vector3d(v[0], v[1], v[2]);
  }
  const Eigen::Vector2d v_t = tangents_.transpose() * v_rel;
  double dr_dv[4];
  FrictionResidual(v_t.data(), 2, eps_v_, residuals, jacobians != nullptr ? dr_dv : nullptr);
  if (jacobians == nullptr) return true;
  // dr/dx_k = dr/dv_t T^T alpha_k slope (row-major 2 x 3).
  const Eigen::Matrix2d d = Eigen::Map<const Eigen::Matrix<double, 2, 2, Eigen::RowMajor>>(dr_dv);
  const Eigen::Matrix<double, 2, 3> base = d * tangents_.transpose();
  for (int k = 0; k < 4; ++k) {
    if (jacobians[k] == nullptr) continue;
    Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>> block(jacobians[k]);
    block = (alpha_[k] * context_->velocity_slope) * base;
  }
  return true;
}

int AddSelfFrictionTerms(const std::vector<SelfFrictionLag>& lags, const StepContext* step,
                         const TermOwner& owner, const FrictionSettings& friction,
                         IncrementalPotential* potential) {
  const double mu = friction.ForSelf();
  if (!(mu > 0.0)) return 0;
  for (const SelfFrictionLag& lag : lags) {
    Term term;
    term.kind = TermKind::kDissipation;
    term.SetOwner(owner);
    term.impulsive = true;
    term.nodes.assign(lag.nodes.begin(), lag.nodes.end());
    term.cost = std::make_unique<SelfFriction>(step, lag.nodes.data(), lag.alpha.data(),
                                               lag.tangents, friction.epsilon_v);
    term.loss = std::make_unique<FrictionLoss>(mu * lag.normal_force);
    potential->AddTerm(std::move(term));
  }
  return static_cast<int>(lags.size());
}

}  // namespace ipstep

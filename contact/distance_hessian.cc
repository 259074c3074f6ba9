#include "contact/distance_hessian.h"

#include <Eigen/Eigenvalues>

#include "geometry/point_edge.h"
#include "geometry/point_triangle.h"
#include "geometry/segment_parameter.h"
#include "geometry/segment_segment.h"

namespace ipstep {
namespace {

// Pseudo-inverse of the symmetric PSD f_ll (m = 1 or 2): eigenvalues at most
// kSingularFraction of the largest are dropped (header: the direction is held
// fixed).
template <int M>
Eigen::Matrix<double, M, M> PseudoInverse(const Eigen::Matrix<double, M, M>& f) {
  if constexpr (M == 1) {
    Eigen::Matrix<double, 1, 1> inverse;
    inverse(0, 0) = f(0, 0) > 0.0 ? 1.0 / f(0, 0) : 0.0;
    return inverse;
  } else {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, M, M>> eigen;
    eigen.computeDirect(f);
    const auto& values = eigen.eigenvalues();
    const double largest = values.cwiseAbs().maxCoeff();
    Eigen::Matrix<double, M, 1> inverted;
    for (int k = 0; k < M; ++k) {
      inverted[k] =
          largest > 0.0 && values[k] > kSingularFraction * largest ? 1.0 / values[k] : 0.0;
    }
    return eigen.eigenvectors() * inverted.asDiagonal() * eigen.eigenvectors().transpose();
  }
}

// Hess d = f_XX - f_Xl f_ll^+ f_lX (header) for P with N moving vertices of
// dimension D, weights w, weight derivatives dw (N x M, the free parameters
// only) and T = dP/dlambda (D x M). False when |P| = 0.
template <int N, int D, int M>
bool EnvelopeHessian(const Eigen::Matrix<double, N, 1>& w, const Eigen::Matrix<double, N, M>& dw,
                     const Eigen::Matrix<double, D, M>& tangents,
                     const Eigen::Matrix<double, D, 1>& p,
                     Eigen::Matrix<double, N * D, N * D>* hessian) {
  using VectorD = Eigen::Matrix<double, D, 1>;
  using MatrixD = Eigen::Matrix<double, D, D>;
  const double r = p.norm();
  if (!(r > 0.0)) return false;
  const VectorD u = p / r;
  const MatrixD q = (MatrixD::Identity() - u * u.transpose()) / r;
  for (int i = 0; i < N; ++i) {
    for (int j = 0; j < N; ++j) {
      hessian->template block<D, D>(i * D, j * D) = (w[i] * w[j]) * q;
    }
  }
  if constexpr (M > 0) {
    const Eigen::Matrix<double, D, M> qt = q * tangents;
    Eigen::Matrix<double, N * D, M> f_xl;
    for (int i = 0; i < N; ++i) {
      f_xl.template block<D, M>(i * D, 0) = u * dw.row(i) + w[i] * qt;
    }
    const Eigen::Matrix<double, M, M> f_ll = tangents.transpose() * qt;
    hessian->noalias() -= f_xl * PseudoInverse<M>(f_ll) * f_xl.transpose();
  }
  return true;
}

bool Free(double parameter) { return parameter > 0.0 && parameter < 1.0; }

// Segment point a + alpha (b - a) against the fixed point c; alpha a free
// parameter or a constant.
bool SegmentHessian(const Eigen::Vector3d& c, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                    double alpha, bool free, Matrix6d* hessian) {
  const Eigen::Vector2d w(1.0 - alpha, alpha);
  const Eigen::Vector3d p = a + alpha * (b - a) - c;
  if (!free) return EnvelopeHessian<2, 3, 0>(w, {}, {}, p, hessian);
  return EnvelopeHessian<2, 3, 1>(w, Eigen::Vector2d(-1.0, 1.0), b - a, p, hessian);
}

}  // namespace

bool PointPointDistanceHessian(const Eigen::Vector3d& x, const Eigen::Vector3d& c,
                               Eigen::Matrix3d* hessian) {
  return EnvelopeHessian<1, 3, 0>(Eigen::Matrix<double, 1, 1>::Ones(), {}, {}, x - c, hessian);
}

bool PointBoxDistanceHessian(const Eigen::Vector3d& y, const Eigen::Vector3d& lower,
                             const Eigen::Vector3d& upper, int dimension,
                             Eigen::Matrix3d* hessian) {
  Eigen::Vector3d outside = Eigen::Vector3d::Zero(), axes = Eigen::Vector3d::Zero();
  for (int k = 0; k < dimension; ++k) {
    if (y[k] < lower[k]) {
      outside[k] = y[k] - lower[k];
      axes[k] = 1.0;
    } else if (y[k] > upper[k]) {
      outside[k] = y[k] - upper[k];
      axes[k] = 1.0;
    }
  }
  if (axes.sum() == 0.0) {
    hessian->setZero();  // inside: minus the distance to the nearest face
    return true;
  }
  const double r = outside.norm();
  if (!(r > 0.0)) return false;
  const Eigen::Vector3d u = outside / r;
  *hessian = (Eigen::Matrix3d(axes.asDiagonal()) - u * u.transpose()) / r;
  return true;
}

bool SegmentPointDistanceHessian(const Eigen::Vector3d& c, const Eigen::Vector3d& a,
                                 const Eigen::Vector3d& b, Matrix6d* hessian) {
  const double alpha = ClosestSegmentParameter(c, a, b);
  return SegmentHessian(c, a, b, alpha, Free(alpha), hessian);
}

bool TrianglePointDistanceHessian(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                  const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                  Matrix9d* hessian) {
  const Eigen::Vector3d w = PointTriangleDistance(p, a, b, c).weights;
  const Eigen::Vector3d* x[3] = {&a, &b, &c};
  const Eigen::Vector3d diff = w[0] * a + w[1] * b + w[2] * c - p;
  int positive[3], count = 0;
  for (int k = 0; k < 3; ++k) {
    if (w[k] > 0.0) positive[count++] = k;
  }
  if (count == 3) {
    // lambda = (beta, gamma): w = (1 - beta - gamma, beta, gamma).
    Eigen::Matrix<double, 3, 2> dw;
    dw << -1.0, -1.0, 1.0, 0.0, 0.0, 1.0;
    Eigen::Matrix<double, 3, 2> tangents;
    tangents << b - a, c - a;
    return EnvelopeHessian<3, 3, 2>(w, dw, tangents, diff, hessian);
  }
  if (count == 2) {
    // lambda = s along the edge from vertex i to vertex j: w_i = 1 - s, w_j = s.
    const int i = positive[0], j = positive[1];
    Eigen::Vector3d dw = Eigen::Vector3d::Zero();
    dw[i] = -1.0;
    dw[j] = 1.0;
    return EnvelopeHessian<3, 3, 1>(w, dw, *x[j] - *x[i], diff, hessian);
  }
  return EnvelopeHessian<3, 3, 0>(w, {}, {}, diff, hessian);
}

bool FixedWeightsDistanceHessian(const Eigen::Vector3d& w, const Eigen::Vector3d& a,
                                 const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                 const Eigen::Vector3d& feature, Matrix9d* hessian) {
  return EnvelopeHessian<3, 3, 0>(w, {}, {}, w[0] * a + w[1] * b + w[2] * c - feature, hessian);
}

bool SegmentSegmentDistanceHessian(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                                   const Eigen::Vector3d& b0, const Eigen::Vector3d& b1,
                                   Matrix6d* hessian) {
  const SegmentSegmentDistanceResult result = SegmentSegmentDistance(a0, a1, b0, b1);
  const double s = result.s, t = result.t;
  const Eigen::Vector2d w(1.0 - s, s);
  const Eigen::Vector3d p = a0 + s * (a1 - a0) - b0 - t * (b1 - b0);
  const Eigen::Vector2d dw_s(-1.0, 1.0);
  const Eigen::Vector3d t_s = a1 - a0, t_t = b0 - b1;
  if (Free(s) && Free(t)) {
    Eigen::Matrix<double, 2, 2> dw;
    dw << dw_s, Eigen::Vector2d::Zero();
    Eigen::Matrix<double, 3, 2> tangents;
    tangents << t_s, t_t;
    return EnvelopeHessian<2, 3, 2>(w, dw, tangents, p, hessian);
  }
  if (Free(s)) return EnvelopeHessian<2, 3, 1>(w, dw_s, t_s, p, hessian);
  if (Free(t)) return EnvelopeHessian<2, 3, 1>(w, Eigen::Vector2d::Zero(), t_t, p, hessian);
  return EnvelopeHessian<2, 3, 0>(w, {}, {}, p, hessian);
}

bool PointEdgeDistanceHessian(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                              const Eigen::Vector2d& b, Matrix6d* hessian) {
  const double alpha = PointEdgeDistance(p, a, b).alpha;
  const Eigen::Vector3d w(1.0, -(1.0 - alpha), -alpha);
  const Eigen::Vector2d diff = p - a - alpha * (b - a);
  if (!Free(alpha)) return EnvelopeHessian<3, 2, 0>(w, {}, {}, diff, hessian);
  return EnvelopeHessian<3, 2, 1>(w, Eigen::Vector3d(0.0, 1.0, -1.0), a - b, diff, hessian);
}

bool PointTriangleDistanceHessian(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                  const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                  Matrix12d* hessian) {
  const Eigen::Vector3d wt = PointTriangleDistance(p, a, b, c).weights;
  const Eigen::Vector3d* x[3] = {&a, &b, &c};
  const Eigen::Vector3d diff = wt[0] * a + wt[1] * b + wt[2] * c - p;
  // Over (p, a, b, c): p enters with weight -1 and no parameter.
  const Eigen::Vector4d w(-1.0, wt[0], wt[1], wt[2]);
  int positive[3], count = 0;
  for (int k = 0; k < 3; ++k) {
    if (wt[k] > 0.0) positive[count++] = k;
  }
  if (count == 3) {
    Eigen::Matrix<double, 4, 2> dw;
    dw << 0.0, 0.0, -1.0, -1.0, 1.0, 0.0, 0.0, 1.0;
    Eigen::Matrix<double, 3, 2> tangents;
    tangents << b - a, c - a;
    return EnvelopeHessian<4, 3, 2>(w, dw, tangents, diff, hessian);
  }
  if (count == 2) {
    const int i = positive[0], j = positive[1];
    Eigen::Vector4d dw = Eigen::Vector4d::Zero();
    dw[1 + i] = -1.0;
    dw[1 + j] = 1.0;
    return EnvelopeHessian<4, 3, 1>(w, dw, *x[j] - *x[i], diff, hessian);
  }
  return EnvelopeHessian<4, 3, 0>(w, {}, {}, diff, hessian);
}

bool EdgeEdgeDistanceHessian(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                             const Eigen::Vector3d& b0, const Eigen::Vector3d& b1,
                             Matrix12d* hessian) {
  const SegmentSegmentDistanceResult result = SegmentSegmentDistance(a0, a1, b0, b1);
  const double s = result.s, t = result.t;
  const Eigen::Vector4d w(1.0 - s, s, -(1.0 - t), -t);
  const Eigen::Vector3d diff = a0 + s * (a1 - a0) - b0 - t * (b1 - b0);
  const Eigen::Vector4d dw_s(-1.0, 1.0, 0.0, 0.0), dw_t(0.0, 0.0, 1.0, -1.0);
  const Eigen::Vector3d t_s = a1 - a0, t_t = b0 - b1;
  const bool free_s = Free(s), free_t = Free(t);
  if (free_s && free_t) {
    Eigen::Matrix<double, 4, 2> dw;
    dw << dw_s, dw_t;
    Eigen::Matrix<double, 3, 2> tangents;
    tangents << t_s, t_t;
    return EnvelopeHessian<4, 3, 2>(w, dw, tangents, diff, hessian);
  }
  if (free_s) return EnvelopeHessian<4, 3, 1>(w, dw_s, t_s, diff, hessian);
  if (free_t) return EnvelopeHessian<4, 3, 1>(w, dw_t, t_t, diff, hessian);
  return EnvelopeHessian<4, 3, 0>(w, {}, {}, diff, hessian);
}

bool ObstacleDistanceHessian(const Obstacle& obstacle, const Eigen::Vector3d& x, double t,
                             Eigen::Matrix3d* hessian) {
  return obstacle.DistanceHessian(x, t, hessian);
}

bool EdgeDistanceHessian(const Obstacle& obstacle, int feature, const Eigen::Vector3d& a,
                         const Eigen::Vector3d& b, double t, Matrix6d* hessian) {
  return SegmentPointDistanceHessian(obstacle.EdgeFeature(feature, t), a, b, hessian);
}

bool EdgePointDistanceHessian(const Obstacle& obstacle, int feature, const Eigen::Vector3d& a,
                              const Eigen::Vector3d& b, double alpha, double t, Matrix6d* hessian) {
  return SegmentHessian(obstacle.EdgeFeature(feature, t), a, b, alpha, false, hessian);
}

bool FaceDistanceHessian(const Obstacle& obstacle, int feature, const Eigen::Vector3d& a,
                         const Eigen::Vector3d& b, const Eigen::Vector3d& c, double t,
                         Matrix9d* hessian) {
  return TrianglePointDistanceHessian(obstacle.FaceFeature(feature, t), a, b, c, hessian);
}

bool FacePointDistanceHessian(const Obstacle& obstacle, int feature, const Eigen::Vector3d& a,
                              const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                              const Eigen::Vector3d& w, double t, Matrix9d* hessian) {
  return FixedWeightsDistanceHessian(w, a, b, c, obstacle.FaceFeature(feature, t), hessian);
}

bool BoxEdgeDistanceHessian(const Obstacle& obstacle, int edge, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, double t, Matrix6d* hessian) {
  Eigen::Vector3d p, q;
  obstacle.BoxEdge(edge, t, &p, &q);
  return SegmentSegmentDistanceHessian(a, b, p, q, hessian);
}

}  // namespace ipstep

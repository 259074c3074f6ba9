// Hessians of the contact distances with respect to the moving vertices (the
// obstacle's feature is fixed in x; its time is a constant). The gap terms
// (contact/contact_terms.h) turn them into their residual curvature
// (Term::curvature): for u = d_hat - d, sum_k c_k Hess r_k = -c_0 Hess d.
//
// Derivation (one formula for every case). Each distance here is
//   d(X) = min over lambda in L of |P(X, lambda)| - R,
//   P(X, lambda) = sum_i w_i(lambda) x_i - c(lambda),
// where X stacks the moving vertices x_i, the weights w_i and the fixed part c
// are affine in the closest-point parameters lambda (segment parameter,
// triangle barycentrics, two segment parameters) and L is a box or simplex.
// For fixed lambda, P is affine in X: P = A X - c with A = w^T (x) I (the
// Kronecker product: block i of A is w_i I). Write r = |P|, u = P / r,
// Q = (I - u u^T) / r (the Hessian of |P| with respect to P), and
// T = dP/dlambda (D x m, columns sum_i (dw_i/dlambda_j) x_i - dc/dlambda_j).
// Then f(X, lambda) = |P| has
//   f_X   = A^T u                                  (block i: w_i u)
//   f_XX  = A^T Q A                                (block ij: w_i w_j Q)
//   f_ll  = T^T Q T                                (T does not depend on lambda)
//   f_Xl  = (dA/dlambda)^T u + A^T Q T             (block i, column j:
//                                                   (dw_i/dlambda_j) u + w_i Q T_j)
// At the minimiser lambda*(X), the parameters strictly inside their bounds
// ("free") satisfy f_l = 0 and those at a bound stay there under small
// motions (where the minimiser is strictly inside its region), so they are
// constants. Envelope theorem: grad d = f_X = A^T u (the existing gradients);
// differentiating f_l(X, lambda*(X)) = 0 gives dlambda*/dX = -f_ll^-1 f_lX over
// the free parameters, hence
//   Hess d = f_XX - f_Xl f_ll^-1 f_lX          (free parameters only).
// With no free parameter (vertex regions, a fixed lagged point) it is
// f_XX = (w w^T) (x) Q. At the minimiser T^T u = 0 for the free columns, so
// f_ll = T^T T / r: singular only when the free directions are degenerate
// (zero-length edges, which the distance code already treats as end points,
// or parallel segments, which it already sends to the boundary). Fallback:
// f_ll^-1 is the pseudo-inverse, eigenvalues below kSingularFraction of the
// largest treated as zero, i.e. such a direction of lambda is held fixed,
// which gives the Hessian of an upper bound of d that touches it at X.
//
// The cases (each function picks the closest point exactly as the distance
// function the gap term uses, so the region matches):
//  * point-plane: d affine, Hessian 0 (plane gaps are Gauss-Newton models);
//  * point-sphere / circle: Q;
//  * point-box (outside): P = y - clamp(y) is zero in the axes where y is
//    within the box's slab (those coordinates of the closest point are the
//    free parameters, T = -e_k): Hess d = (S - u u^T) / r, S the diagonal
//    projector onto the axes outside the slab (face region: 0; edge: a 2 x 2
//    block; corner: Q). Inside the box d is minus the distance to the nearest
//    face, affine: 0;
//  * segment vs point feature: w = (1 - alpha, alpha), dw/dalpha = (-1, 1),
//    T = b - a, alpha free strictly inside (0, 1); lagged alpha: fixed;
//  * triangle vs point feature: interior (all weights > 0): lambda = (beta,
//    gamma), w = (1 - beta - gamma, beta, gamma), T = [b - a, c - a]; edge
//    (two weights > 0): one parameter along that edge; vertex: none; lagged
//    weights: fixed;
//  * segment [a, b] vs a fixed segment [p, q] (box edge): P = a + s (b - a) -
//    p - t (q - p), w = (1 - s, s), dw/ds = (-1, 1), dw/dt = 0,
//    T = [b - a, -(q - p)], each of s, t free strictly inside (0, 1);
//  * 2D point p vs segment [a, b], all three moving: P = p - a - alpha (b - a),
//    w = (1, -(1 - alpha), -alpha), dw/dalpha = (0, 1, -1), T = -(b - a);
//  * 3D self-contact, all four points moving (contact/pairs/):
//    point p vs triangle [a, b, c]: P = w_a a + w_b b + w_c c - p, so the
//    weights over (p, a, b, c) are (-1, w_a, w_b, w_c) with the free
//    barycentric parameters of the triangle case above (dw of p is 0);
//    segment [a0, a1] vs segment [b0, b1]: P = a0 + s (a1 - a0) - b0 -
//    t (b1 - b0), w = (1 - s, s, -(1 - t), -t), dw/ds = (-1, 1, 0, 0),
//    dw/dt = (0, 0, 1, -1), T = [a1 - a0, -(b1 - b0)], each of s, t free
//    strictly inside (0, 1).
//
// All positions are 3D (2D callers pass z = 0: the Hessian of the restriction
// to the plane is the top-left 2 x 2 block of each 3 x 3 vertex block). Hessians
// are over the moving vertices in order, 3 coordinates each (the 2D point-edge
// case: 2 each). Every function returns false where |P| = 0 (no direction; the
// gap terms fail there anyway), leaving the output unspecified. Fixed-size
// Eigen types only: no heap allocation.
#pragma once

#include <Eigen/Core>

#include "contact/obstacle.h"

namespace ipstep {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Matrix9d = Eigen::Matrix<double, 9, 9>;
using Matrix12d = Eigen::Matrix<double, 12, 12>;

// Eigenvalues of f_ll below this fraction of its largest are treated as zero.
constexpr double kSingularFraction = 1e-14;

// Geometry. Point x against the fixed point c: (I - u u^T) / |x - c|.
bool PointPointDistanceHessian(const Eigen::Vector3d& x, const Eigen::Vector3d& c,
                               Eigen::Matrix3d* hessian);
// Point y against the box [lower, upper] (first `dimension` axes), the
// distance of Obstacle::Distance: outside, the distance to the clamped point.
bool PointBoxDistanceHessian(const Eigen::Vector3d& y, const Eigen::Vector3d& lower,
                             const Eigen::Vector3d& upper, int dimension, Eigen::Matrix3d* hessian);
// Segment [a, b] (moving) against the fixed point c: over (a, b), the closest
// point's parameter ClosestSegmentParameter(c, a, b).
bool SegmentPointDistanceHessian(const Eigen::Vector3d& c, const Eigen::Vector3d& a,
                                 const Eigen::Vector3d& b, Matrix6d* hessian);
// Triangle [a, b, c] (moving) against the fixed point p (PointTriangleDistance).
bool TrianglePointDistanceHessian(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                  const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                  Matrix9d* hessian);
// |w[0] a + w[1] b + w[2] c - feature| for fixed weights w: (w w^T) (x) Q.
bool FixedWeightsDistanceHessian(const Eigen::Vector3d& w, const Eigen::Vector3d& a,
                                 const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                 const Eigen::Vector3d& feature, Matrix9d* hessian);
// Segment [a0, a1] (moving) against the fixed segment [b0, b1]
// (SegmentSegmentDistance): over (a0, a1).
bool SegmentSegmentDistanceHessian(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                                   const Eigen::Vector3d& b0, const Eigen::Vector3d& b1,
                                   Matrix6d* hessian);
// 2D point p against the segment [a, b], all moving (PointEdgeDistance): over
// (p, a, b), 2 coordinates each.
bool PointEdgeDistanceHessian(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                              const Eigen::Vector2d& b, Matrix6d* hessian);

// Point p against the triangle [a, b, c], all moving (PointTriangleDistance):
// over (p, a, b, c).
bool PointTriangleDistanceHessian(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                  const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                  Matrix12d* hessian);
// Segment [a0, a1] against segment [b0, b1], all moving
// (SegmentSegmentDistance): over (a0, a1, b0, b1).
bool EdgeEdgeDistanceHessian(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                             const Eigen::Vector3d& b0, const Eigen::Vector3d& b1,
                             Matrix12d* hessian);

// Obstacles at time t (their features fixed): the Hessians of the distances of
// Obstacle (contact/obstacle.h) with the same arguments.
// Obstacle::Distance: plane 0, sphere / circle, box.
bool ObstacleDistanceHessian(const Obstacle& obstacle, const Eigen::Vector3d& x, double t,
                             Eigen::Matrix3d* hessian);
// Obstacle::EdgeDistance, over (a, b).
bool EdgeDistanceHessian(const Obstacle& obstacle, int feature, const Eigen::Vector3d& a,
                         const Eigen::Vector3d& b, double t, Matrix6d* hessian);
// Obstacle::EdgePointDistance (fixed alpha), over (a, b).
bool EdgePointDistanceHessian(const Obstacle& obstacle, int feature, const Eigen::Vector3d& a,
                              const Eigen::Vector3d& b, double alpha, double t, Matrix6d* hessian);
// Obstacle::FaceDistance, over (a, b, c).
bool FaceDistanceHessian(const Obstacle& obstacle, int feature, const Eigen::Vector3d& a,
                         const Eigen::Vector3d& b, const Eigen::Vector3d& c, double t,
                         Matrix9d* hessian);
// Obstacle::FacePointDistance (fixed weights w), over (a, b, c).
bool FacePointDistanceHessian(const Obstacle& obstacle, int feature, const Eigen::Vector3d& a,
                              const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                              const Eigen::Vector3d& w, double t, Matrix9d* hessian);
// Obstacle::BoxEdgeDistance, over (a, b).
bool BoxEdgeDistanceHessian(const Obstacle& obstacle, int edge, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, double t, Matrix6d* hessian);

}  // namespace ipstep

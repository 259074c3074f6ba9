// IPC's mollifier of the edge-edge barrier for nearly parallel edges (Li et
// al. 2020, section 4.3): two edges [a0, a1], [b0, b1] with directions
// e0 = a1 - a0, e1 = b1 - b0 and
//   c = |e0 x e1|^2 = |e0|^2 |e1|^2 - (e0 . e1)^2,
//   eps_x = 1e-3 |e0_rest|^2 |e1_rest|^2,
//   m(c) = (2 - c / eps_x) c / eps_x   for c < eps_x,   1 otherwise.
// The edge-edge barrier is m(c) b(d): as the edges turn parallel the closest
// points jump along the overlap and d is not smooth there; m goes to zero
// there (with its derivative m'(eps_x) = 0 at the switch, so m is C^1).
//
// Derivatives over x = (a0, a1, b0, b1) (12 coordinates). With e0 = a1 - a0,
// e1 = b1 - b0 (so de0/dx = [-I, I, 0, 0], de1/dx = [0, 0, -I, I]):
//   dc/de0 = 2 |e1|^2 e0 - 2 (e0.e1) e1,   dc/de1 = 2 |e0|^2 e1 - 2 (e0.e1) e0,
//   d2c/de0de0 = 2 |e1|^2 I - 2 e1 e1^T,   d2c/de1de1 = 2 |e0|^2 I - 2 e0 e0^T,
//   d2c/de0de1 = 4 e0 e1^T - 2 e1 e0^T - 2 (e0.e1) I,
//   m'(c) = 2 (1 - c / eps_x) / eps_x,   m''(c) = -2 / eps_x^2   (c < eps_x),
//   grad m = m' grad c,   Hess m = m'' grad c grad c^T + m' Hess c.
#pragma once

#include <Eigen/Core>

namespace ipstep {

using Vector12d = Eigen::Matrix<double, 12, 1>;

constexpr double kMollifierFraction = 1e-3;

// eps_x of two edges from their rest lengths squared.
inline double MollifierThreshold(double rest_length2_a, double rest_length2_b) {
  return kMollifierFraction * rest_length2_a * rest_length2_b;
}

struct EdgeEdgeMollifier {
  double value = 1.0;                      // m
  Vector12d gradient = Vector12d::Zero();  // grad m over (a0, a1, b0, b1)
  Eigen::Matrix<double, 12, 12> hessian =  // Hess m
      Eigen::Matrix<double, 12, 12>::Zero();
  bool active() const { return value < 1.0; }  // c < eps_x
};

// m, and its derivatives when `derivatives` (the Hessian only when `hessian`).
EdgeEdgeMollifier EdgeEdgeMollify(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                                  const Eigen::Vector3d& b0, const Eigen::Vector3d& b1,
                                  double eps_x, bool derivatives = true, bool hessian = true);

}  // namespace ipstep

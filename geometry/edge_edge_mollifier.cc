#include "geometry/edge_edge_mollifier.h"

#include <algorithm>

namespace ipstep {

EdgeEdgeMollifier EdgeEdgeMollify(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                                  const Eigen::Vector3d& b0, const Eigen::Vector3d& b1,
                                  double eps_x, bool derivatives, bool hessian) {
  EdgeEdgeMollifier m;
  const Eigen::Vector3d e0 = a1 - a0, e1 = b1 - b0;
  const double l0 = e0.squaredNorm(), l1 = e1.squaredNorm(), dot = e0.dot(e1);
  const double c = std::max(l0 * l1 - dot * dot, 0.0);
  if (!(eps_x > 0.0) || c >= eps_x) return m;
  const double ratio = c / eps_x;
  m.value = (2.0 - ratio) * ratio;
  if (!derivatives) return m;
  const double m1 = 2.0 * (1.0 - ratio) / eps_x;
  // grad c over (e0, e1), then over x by de0/dx = [-I, I, 0, 0], de1/dx = [0, 0, -I, I].
  const Eigen::Vector3d g0 = 2.0 * l1 * e0 - 2.0 * dot * e1;
  const Eigen::Vector3d g1 = 2.0 * l0 * e1 - 2.0 * dot * e0;
  Vector12d grad_c;
  grad_c << -g0, g0, -g1, g1;
  m.gradient = m1 * grad_c;
  if (!hessian) return m;
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d h00 = 2.0 * l1 * identity - 2.0 * e1 * e1.transpose();
  const Eigen::Matrix3d h11 = 2.0 * l0 * identity - 2.0 * e0 * e0.transpose();
  const Eigen::Matrix3d h01 =
      4.0 * e0 * e1.transpose() - 2.0 * e1 * e0.transpose() - 2.0 * dot * identity;
  // Block (i, j) of Hess c over x: sign_i sign_j h(edge_i, edge_j), signs (-, +) per edge.
  const double sign[4] = {-1.0, 1.0, -1.0, 1.0};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const bool ei = i >= 2, ej = j >= 2;
      Eigen::Matrix3d block;
      if (!ei && !ej) {
        block = h00;
      } else if (ei && ej) {
        block = h11;
      } else if (!ei) {
        block = h01;
      } else {
        block = h01.transpose();
      }
      m.hessian.block<3, 3>(3 * i, 3 * j) = (sign[i] * sign[j] * m1) * block;
    }
  }
  m.hessian.noalias() += (-2.0 / (eps_x * eps_x)) * grad_c * grad_c.transpose();
  return m;
}

}  // namespace ipstep

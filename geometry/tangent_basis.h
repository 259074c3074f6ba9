// Orthonormal tangent basis of the plane (3D) or line (2D) orthogonal to a
// unit normal, for the friction terms' lagged tangential velocity.
#pragma once

#include <Eigen/Core>

namespace ipstep {

// Columns: dimension - 1 unit tangents orthogonal to unit n (and to each
// other); the remaining columns are zero. 2D: n rotated by +90 degrees. 3D:
// n x e_k with e_k the axis least aligned with n, then n x that.
Eigen::Matrix3d TangentBasis(const Eigen::Vector3d& n, int dimension);

}  // namespace ipstep

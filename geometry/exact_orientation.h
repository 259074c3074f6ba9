// Exact signs of the 2D and 3D orientation determinants of double inputs.
//
// orient3d(a, b, c, d) = det [a - d; b - d; c - d] (rows), orient2d(a, b, c)
// = det [b - a; c - a]. First evaluated in double with a forward error bound
// (the standard bound for these formulas: relative error of the computed
// determinant at most (7 + 56 eps) eps resp. (3 + 16 eps) eps times the
// permanent, the same expression with every product and difference taken in
// absolute value, eps = 2^-53); when |det| exceeds it the sign is certain.
// Otherwise the determinant is recomputed exactly as a floating-point
// expansion (a sum of doubles that represents the value exactly):
//  * TwoSum(a, b) = (x, y) with x = fl(a + b) and x + y = a + b exactly
//    (Knuth's branch-free error of a rounded sum);
//  * TwoProduct(a, b) = (x, y) with x = fl(a b), y = fma(a, b, -x) exact;
//  * adding a double b to an expansion e (components nonoverlapping, of
//    increasing magnitude): carry q = b through the components, q, h_i =
//    TwoSum(q, e_i), output h_1 .. h_m, q: again nonoverlapping and
//    increasing (zero components dropped), and exact;
//  * sums and products of expansions by repeated additions of their
//    components' exact sums and TwoProducts.
// The sign of an expansion is that of its largest nonzero component, the
// last one. Inputs must be finite and far from overflow and underflow.
#pragma once

#include <Eigen/Core>

namespace ipstep {

// Sign (-1, 0, +1) of orient3d(a, b, c, d).
int ExactOrient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  const Eigen::Vector3d& d);
// Sign of orient2d of (a, b, c) in the coordinates (i, j).
int ExactOrient2d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  int i, int j);

}  // namespace ipstep

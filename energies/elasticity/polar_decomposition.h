// The rotation R of the polar decomposition F = R S (S symmetric positive
// definite) for det F > 0, written for any scalar type (double, long double,
// ceres::Jet) so that autodiff differentiates it.
//
// 2D, closed form: R is the rotation by the angle theta that maximises
// tr(R^T F) = cos(theta)(F00 + F11) + sin(theta)(F10 - F01), so
//   R = [[c, -s], [s, c]] / sqrt(c^2 + s^2),  c = F00 + F11,  s = F10 - F01.
// c^2 + s^2 > 0 whenever det F > 0 (c = s = 0 means F = [[a, b], [b, -a]],
// det F = -a^2 - b^2 <= 0), so R is smooth there.
//
// 3D: Newton's iteration for the orthogonal polar factor with Higham's scaling,
//   X_0 = F,  X_{k+1} = (zeta_k X_k + X_k^{-T} / zeta_k) / 2,
//   zeta_k = (|X_k^{-1}|_F / |X_k|_F)^{1/2}   (scaling switched off near convergence),
// which converges quadratically to R for any nonsingular F (det F > 0 keeps
// every X_k at det > 0). Chosen over an SVD because it is a short chain of
// smooth operations, so autodiff differentiates it as it is: the derivatives
// of the iterates converge with the iterates (the map is analytic and its
// derivative at the fixed point R is the projection onto the tangent space of
// the rotations), and two iterations after the value has converged they agree
// with dR/dF to round-off (tests/energies/elasticity_test.cc checks the energy's
// gradient against finite differences). An SVD would need special care at
// repeated singular values (F = I at rest), where its factors are not
// differentiable although R is.
#pragma once

#include <cmath>

#include <ceres/jet.h>

namespace ipstep {

// The value of a scalar without its derivative parts.
inline double ScalarPart(double v) { return v; }
inline long double ScalarPart(long double v) { return v; }
template <typename T, int N>
double ScalarPart(const ceres::Jet<T, N>& v) {
  return static_cast<double>(ScalarPart(v.a));
}

template <typename T>
void PolarRotation2(const T F[2][2], T R[2][2]) {
  using std::sqrt;
  const T c = F[0][0] + F[1][1];
  const T s = F[1][0] - F[0][1];
  const T n = sqrt(c * c + s * s);
  R[0][0] = c / n;
  R[0][1] = -s / n;
  R[1][0] = s / n;
  R[1][1] = c / n;
}

template <typename T>
T Determinant3(const T A[3][3]) {
  return A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
         A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
         A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
}

// Inverse transpose of A: cofactor(A) / det A.
template <typename T>
void InverseTranspose3(const T A[3][3], T out[3][3]) {
  const T det = Determinant3(A);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      out[i][j] = (A[i1][j1] * A[i2][j2] - A[i1][j2] * A[i2][j1]) / det;
    }
  }
}

// Returns false if the iteration does not converge (det F <= 0 or non-finite F).
template <typename T>
bool PolarRotation3(const T F[3][3], T R[3][3]) {
  using std::sqrt;
  T X[3][3], Y[3][3];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) X[i][j] = F[i][j];
  }
  int settled = -1;  // iterations done after the value converged
  for (int k = 0; k < 60; ++k) {
    if (!(Determinant3(X) > 0.0)) return false;
    InverseTranspose3(X, Y);
    T norm_x(0.0), norm_y(0.0);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        norm_x += X[i][j] * X[i][j];
        norm_y += Y[i][j] * Y[i][j];
      }
    }
    // |X^{-1}|_F = |X^{-T}|_F. Scaling only while far from the fixed point.
    T zeta(1.0);
    if (settled < 0 && k < 6) zeta = sqrt(sqrt(norm_y / norm_x));
    double change = 0.0;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        const T next = 0.5 * (zeta * X[i][j] + Y[i][j] / zeta);
        const T diff = next - X[i][j];
        change += static_cast<double>(ScalarPart(diff) * ScalarPart(diff));
        X[i][j] = next;
      }
    }
    if (settled >= 0) ++settled;
    if (settled < 0 && change < 1e-26) settled = 0;
    if (settled >= 2) {
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) R[i][j] = X[i][j];
      }
      return true;
    }
  }
  return false;
}

}  // namespace ipstep

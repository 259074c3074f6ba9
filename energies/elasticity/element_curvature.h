// Analytic second derivatives of the element residuals (element_energy.h) for
// the Newton models: Term::curvature (core/term.h) asks for
//   C = sum_k c_k Hess r_k(x)
// over the element's (d + 1) d coordinates, row-major, coordinate a d + i =
// component i of node a. Without it core/term_hessian.h takes central
// differences of the autodiff Jacobian (2 n Jacobian evaluations, n = 6 or 12).
//
// Notation. F = Ds Dm^{-1} is linear in x: dF_ij = sum_a dx_{a,i} D_aj with the
// shape-function gradients D_a = row a-1 of Dm^{-1} (a >= 1) and
// D_0 = -(D_1 + ... + D_d). So a function f(F) with derivatives
// A_ijkl = d2f / dF_ij dF_kl has, over x,
//   Hess_x f [(a,i),(b,k)] = sum_jl A_ijkl D_aj D_bl.                      (1)
// G = F^{-T}, J = det F, and g_a = G D_a^T (a d-vector per node).
//
// neo_hookean. Psi = mu/2 (|F|^2 - d) - mu ln J + lambda/2 (ln J)^2. With
// d ln J = G : dF and dG = -G dF^T G:
//   P = dPsi/dF = mu (F - G) + lambda ln J G,
//   dP = mu dF + (mu - lambda ln J) G dF^T G + lambda (G : dF) G,
//   A_ijkl = mu d_ik d_jl + (mu - lambda ln J) G_il G_kj + lambda G_ij G_kl,
// and by (1), with e = V Psi,
//   grad e [(a,i)] = V (mu (F D_a^T)_i + (lambda ln J - mu) g_a[i]),
//   Hess e [(a,i),(b,k)] = V (mu (D_a . D_b) d_ik
//                             + (mu - lambda ln J) g_b[i] g_a[k] + lambda g_a[i] g_b[k]).
// The residual is r = sqrt(s), s = 2 e + c0 (one residual), so
//   grad r = grad e / r,  Hess r = Hess e / r - grad e grad e^T / r^3,
// and C = c_0 Hess r. (With c_0 = r, the Newton model's J^T J + r Hess r is
// grad e grad e^T / r^2 + Hess e - grad e grad e^T / r^2 = Hess e: exact.)
//
// stvk. Every residual is linear in the Green strain E = (F^T F - I)/2:
// r_k = sum_ij L_kij E_ij (element_energy.h: diagonal deviator, off-diagonal,
// trace). So sum_k c_k r_k = sum_ij M_ij E_ij = tr(F M F^T)/2 with the
// symmetric M = sym(sum_k c_k L_k), whose second differential is
// tr(dF M dF^T) = sum_ab (dx_a . dx_b) D_a M D_b^T:
//   C [(a,i),(b,k)] = d_ik D_a M D_b^T,
//   M_ii = a_d c_i - (a_d / d) sum_{j<d} c_j + a_t c_t,  M_ij = M_ji = a_o c_(ij) / 2,
// a_d, a_o, a_t the diagonal, off-diagonal and trace coefficients and c_(ij)
// the coefficient of the residual of E_ij (i < j).
//
// fixed_corotated (2D only; 3D keeps the central differences). The residuals
// are s (F - R)_ij (F linear: no curvature) and t (J - 1), t = sqrt(lambda V):
//   C = -s Hess(sum_ij c_ij R_ij) + c_t t Hess J.
// Hess J: d(J G) = J (G : dF) G - J G dF^T G, so d2J/dF_ij dF_kl =
// J (G_ij G_kl - G_il G_kj) and by (1)
//   Hess_x J [(a,i),(b,k)] = J (g_a[i] g_b[k] - g_b[i] g_a[k])   (2D and 3D).
// The 2D rotation (polar_decomposition.h) is R = [[u0, -u1], [u1, u0]],
// u = q / |q|, q = (F00 + F11, F10 - F01), so sum_ij c_ij R_ij = w . u with
// w = (c00 + c11, c10 - c01), and with rho = |q|
//   Hess_q (w . q / rho) = -(w q^T + q w^T) / rho^3 - (w . q) (I / rho^3 - 3 q q^T / rho^5).
// q is linear in x: dq = Q dx with Q[0,(a,0)] = D_a0, Q[0,(a,1)] = D_a1,
// Q[1,(a,0)] = -D_a1, Q[1,(a,1)] = D_a0, so Hess_x = Q^T Hess_q Q.
//
// linear: affine residuals, no curvature (its Gauss-Newton model is exact).
#pragma once

#include <cmath>

#include "problems/elastic_material.h"

namespace ipstep {

// True for the models whose ElasticElement has an analytic curvature below.
constexpr bool HasAnalyticCurvature(ElasticModel model, int dim) {
  return model == ElasticModel::kNeoHookean || model == ElasticModel::kStvk ||
         (model == ElasticModel::kFixedCorotated && dim == 2);
}

namespace element_curvature {

// F, J, G = F^{-T} and the shape-function gradients D_a (rows of D) from the
// positions x (d + 1 nodes) and Dm^{-1}. False where J <= 0.
template <int kDim>
bool Kinematics(const double* const* x, const double (&dm_inv)[kDim][kDim], double (&F)[kDim][kDim],
                double& J, double (&G)[kDim][kDim], double (&D)[kDim + 1][kDim]) {
  double ds[kDim][kDim];
  for (int c = 0; c < kDim; ++c) {
    for (int k = 0; k < kDim; ++k) ds[k][c] = x[c + 1][k] - x[0][k];
  }
  for (int i = 0; i < kDim; ++i) {
    for (int j = 0; j < kDim; ++j) {
      F[i][j] = 0.0;
      for (int k = 0; k < kDim; ++k) F[i][j] += ds[i][k] * dm_inv[k][j];
    }
  }
  for (int j = 0; j < kDim; ++j) {
    D[0][j] = 0.0;
    for (int a = 1; a <= kDim; ++a) {
      D[a][j] = dm_inv[a - 1][j];
      D[0][j] -= D[a][j];
    }
  }
  if constexpr (kDim == 2) {
    J = F[0][0] * F[1][1] - F[0][1] * F[1][0];
    if (!(J > 0.0)) return false;
    G[0][0] = F[1][1] / J;
    G[0][1] = -F[1][0] / J;
    G[1][0] = -F[0][1] / J;
    G[1][1] = F[0][0] / J;
  } else {
    // Cofactors: G = cof(F) / J.
    const double c[3][3] = {
        {F[1][1] * F[2][2] - F[1][2] * F[2][1], F[1][2] * F[2][0] - F[1][0] * F[2][2],
         F[1][0] * F[2][1] - F[1][1] * F[2][0]},
        {F[0][2] * F[2][1] - F[0][1] * F[2][2], F[0][0] * F[2][2] - F[0][2] * F[2][0],
         F[0][1] * F[2][0] - F[0][0] * F[2][1]},
        {F[0][1] * F[1][2] - F[0][2] * F[1][1], F[0][2] * F[1][0] - F[0][0] * F[1][2],
         F[0][0] * F[1][1] - F[0][1] * F[1][0]}};
    J = F[0][0] * c[0][0] + F[0][1] * c[0][1] + F[0][2] * c[0][2];
    if (!(J > 0.0)) return false;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) G[i][j] = c[i][j] / J;
    }
  }
  return true;
}

// g_a = G D_a^T for every node a.
template <int kDim>
void InverseGradients(const double (&G)[kDim][kDim], const double (&D)[kDim + 1][kDim],
                      double (&g)[kDim + 1][kDim]) {
  for (int a = 0; a <= kDim; ++a) {
    for (int i = 0; i < kDim; ++i) {
      g[a][i] = 0.0;
      for (int j = 0; j < kDim; ++j) g[a][i] += G[i][j] * D[a][j];
    }
  }
}

template <int kDim>
bool NeoHookean(const double* const* x, const double (&dm_inv)[kDim][kDim], double volume,
                double mu, double lambda, double offset, double c0, double* curvature) {
  constexpr int n = (kDim + 1) * kDim;
  double F[kDim][kDim], J, G[kDim][kDim], D[kDim + 1][kDim], g[kDim + 1][kDim];
  if (!Kinematics<kDim>(x, dm_inv, F, J, G, D)) return false;
  InverseGradients<kDim>(G, D, g);
  const double log_j = std::log(J);
  double norm2 = 0.0;
  for (int i = 0; i < kDim; ++i) {
    for (int j = 0; j < kDim; ++j) norm2 += F[i][j] * F[i][j];
  }
  const double psi = 0.5 * mu * (norm2 - kDim) - mu * log_j + 0.5 * lambda * log_j * log_j;
  const double s = 2.0 * volume * psi + offset;
  if (!(s > 0.0)) return false;
  const double r = std::sqrt(s);
  // grad e.
  double grad[n];
  for (int a = 0; a <= kDim; ++a) {
    for (int i = 0; i < kDim; ++i) {
      double fd = 0.0;
      for (int j = 0; j < kDim; ++j) fd += F[i][j] * D[a][j];
      grad[a * kDim + i] = volume * (mu * fd + (lambda * log_j - mu) * g[a][i]);
    }
  }
  // C = c0 (Hess e / r - grad e grad e^T / r^3).
  const double scale = c0 / r;
  const double outer = c0 / (r * r * r);
  const double cross = volume * (mu - lambda * log_j);
  for (int a = 0; a <= kDim; ++a) {
    for (int b = 0; b <= kDim; ++b) {
      double dd = 0.0;
      for (int j = 0; j < kDim; ++j) dd += D[a][j] * D[b][j];
      for (int i = 0; i < kDim; ++i) {
        for (int k = 0; k < kDim; ++k) {
          const int row = a * kDim + i, col = b * kDim + k;
          double h = cross * g[b][i] * g[a][k] + volume * lambda * g[a][i] * g[b][k];
          if (i == k) h += volume * mu * dd;
          curvature[row * n + col] = scale * h - outer * grad[row] * grad[col];
        }
      }
    }
  }
  return true;
}

// c: the residual coefficients in element_energy.h's order (d diagonal
// deviators, the off-diagonals (i < j), the trace).
template <int kDim>
bool Stvk(const double* const* x, const double (&dm_inv)[kDim][kDim], double volume, double mu,
          double lambda, const double* c, double* curvature) {
  constexpr int n = (kDim + 1) * kDim;
  double F[kDim][kDim], J, G[kDim][kDim], D[kDim + 1][kDim];
  if (!Kinematics<kDim>(x, dm_inv, F, J, G, D)) return false;
  const double diagonal = std::sqrt(2.0 * mu * volume);
  const double off_diagonal = std::sqrt(4.0 * mu * volume);
  const double bulk = std::sqrt((lambda + 2.0 * mu / kDim) * volume);
  double M[kDim][kDim];
  double deviator_sum = 0.0;
  for (int i = 0; i < kDim; ++i) deviator_sum += c[i];
  const double trace = c[kDim * (kDim + 1) / 2];
  int m = kDim;
  for (int i = 0; i < kDim; ++i) {
    M[i][i] = diagonal * (c[i] - deviator_sum / kDim) + bulk * trace;
    for (int j = i + 1; j < kDim; ++j) {
      M[i][j] = M[j][i] = 0.5 * off_diagonal * c[m++];
    }
  }
  for (int a = 0; a <= kDim; ++a) {
    for (int b = 0; b <= kDim; ++b) {
      double dmd = 0.0;
      for (int j = 0; j < kDim; ++j) {
        for (int l = 0; l < kDim; ++l) dmd += D[a][j] * M[j][l] * D[b][l];
      }
      for (int i = 0; i < kDim; ++i) {
        for (int k = 0; k < kDim; ++k) {
          curvature[(a * kDim + i) * n + b * kDim + k] = i == k ? dmd : 0.0;
        }
      }
    }
  }
  return true;
}

// 2D only (HasAnalyticCurvature). c: the four (F - R)_ij coefficients
// row-major, then the (J - 1) one.
inline bool FixedCorotated2(const double* const* x, const double (&dm_inv)[2][2], double volume,
                            double mu, double lambda, const double* c, double* curvature) {
  constexpr int n = 6;
  double F[2][2], J, G[2][2], D[3][2], g[3][2];
  if (!Kinematics<2>(x, dm_inv, F, J, G, D)) return false;
  InverseGradients<2>(G, D, g);
  const double shear = std::sqrt(2.0 * mu * volume);
  const double bulk = std::sqrt(lambda * volume) * c[4];
  const double q[2] = {F[0][0] + F[1][1], F[1][0] - F[0][1]};
  const double w[2] = {c[0] + c[3], c[2] - c[1]};
  const double rho2 = q[0] * q[0] + q[1] * q[1];
  const double rho = std::sqrt(rho2);
  const double rho3 = rho2 * rho;
  const double wq = w[0] * q[0] + w[1] * q[1];
  double hq[2][2];
  for (int p = 0; p < 2; ++p) {
    for (int t = 0; t < 2; ++t) {
      hq[p][t] = -(w[p] * q[t] + q[p] * w[t]) / rho3 -
                 wq * ((p == t ? 1.0 : 0.0) / rho3 - 3.0 * q[p] * q[t] / (rho3 * rho2));
    }
  }
  // Q: 2 x 6.
  double Q[2][n];
  for (int a = 0; a < 3; ++a) {
    Q[0][2 * a] = D[a][0];
    Q[0][2 * a + 1] = D[a][1];
    Q[1][2 * a] = -D[a][1];
    Q[1][2 * a + 1] = D[a][0];
  }
  for (int a = 0; a < 3; ++a) {
    for (int i = 0; i < 2; ++i) {
      const int row = 2 * a + i;
      for (int b = 0; b < 3; ++b) {
        for (int k = 0; k < 2; ++k) {
          const int col = 2 * b + k;
          double rotation = 0.0;
          for (int p = 0; p < 2; ++p) {
            for (int t = 0; t < 2; ++t) rotation += Q[p][row] * hq[p][t] * Q[t][col];
          }
          const double det = J * (g[a][i] * g[b][k] - g[b][i] * g[a][k]);
          curvature[row * n + col] = -shear * rotation + bulk * det;
        }
      }
    }
  }
  return true;
}

}  // namespace element_curvature
}  // namespace ipstep

// The isotropic energy densities of element_energy.h as functions of the
// singular values sigma of F (rotation-variant SVD F = U diag(sigma) V^T,
// det U = det V = 1, sigma > 0 for J = det F > 0): the value, the gradient
// Psi_i = dPsi/dsigma_i, the Hessian Psi_ij, and for every pair i < j the
// twist and flip eigenvalues of the F-space Hessian (isotropic_eigensystem.h)
//   twist = (Psi_i + Psi_j) / (sigma_i + sigma_j),
//   flip  = (Psi_i - Psi_j) / (sigma_i - sigma_j),
// each written out per energy so that no flip divides by sigma_i - sigma_j
// (exact at F = I, on the rotations and at repeated singular values). At
// sigma_i = sigma_j the flip is the limit Psi_ii - Psi_ij, the curvature of
// the scaling mode e_i - e_j.
//
// J = prod_k sigma_k, so dJ/dsigma_i = J / sigma_i and
// d2J/dsigma_i dsigma_j = J / (sigma_i sigma_j) (i != j), 0 (i = j);
// J / (sigma_i sigma_j) is the product of the other singular values: sigma_k
// in 3D (k the third index), 1 in 2D (OtherProduct below).
//
// neo_hookean. Psi = mu/2 (sum sigma_k^2 - d) - mu ln J + lambda/2 (ln J)^2
// (|F|^2 = sum sigma_k^2, ln J = sum ln sigma_k):
//   Psi_i = mu sigma_i + (lambda ln J - mu) / sigma_i,
//   Psi_ii = mu + (mu + lambda - lambda ln J) / sigma_i^2,
//   Psi_ij = lambda / (sigma_i sigma_j),
//   twist = [mu (s_i + s_j) + (lambda ln J - mu)(1/s_i + 1/s_j)] / (s_i + s_j)
//         = mu + (lambda ln J - mu) / (s_i s_j),
//   flip  = [mu (s_i - s_j) + (lambda ln J - mu)(s_j - s_i) / (s_i s_j)] / (s_i - s_j)
//         = mu + (mu - lambda ln J) / (s_i s_j).
//
// stvk. E = V diag((sigma_k^2 - 1)/2) V^T, so with T = tr E = sum (s_k^2 - 1)/2
// Psi = mu/4 sum (s_k^2 - 1)^2 + lambda/2 T^2:
//   Psi_i = mu (s_i^2 - 1) s_i + lambda T s_i,
//   Psi_ii = mu (3 s_i^2 - 1) + lambda (T + s_i^2),
//   Psi_ij = lambda s_i s_j,
//   twist = lambda T + mu (s_i^3 + s_j^3 - s_i - s_j) / (s_i + s_j)
//         = lambda T + mu (s_i^2 - s_i s_j + s_j^2 - 1),
//   flip  = lambda T + mu (s_i^3 - s_j^3 - s_i + s_j) / (s_i - s_j)
//         = lambda T + mu (s_i^2 + s_i s_j + s_j^2 - 1).
//
// fixed_corotated. R = U V^T, so |F - R|^2 = sum (s_k - 1)^2 and
// Psi = mu sum (s_k - 1)^2 + lambda/2 (J - 1)^2; with g_i = J / s_i and
// o_ij = J / (s_i s_j):
//   Psi_i = 2 mu (s_i - 1) + lambda (J - 1) g_i,
//   Psi_ii = 2 mu + lambda g_i^2,
//   Psi_ij = lambda (g_i g_j + (J - 1) o_ij) = lambda (2 J - 1) o_ij,
//   twist = [2 mu (s_i + s_j - 2) + lambda (J - 1) J (1/s_i + 1/s_j)] / (s_i + s_j)
//         = 2 mu (1 - 2 / (s_i + s_j)) + lambda (J - 1) o_ij,
//   flip  = [2 mu (s_i - s_j) + lambda (J - 1) J (s_j - s_i) / (s_i s_j)] / (s_i - s_j)
//         = 2 mu - lambda (J - 1) o_ij.
//
// linear is not isotropic in this sense (eps = sym(F) - I is not invariant
// under F -> R F): not handled here.
#pragma once

#include <cmath>

#include <Eigen/Core>

#include "problems/elastic_material.h"

namespace ipstep {

template <int kDim>
struct SingularValueEnergy {
  static constexpr int kPairs = kDim * (kDim - 1) / 2;
  double psi = 0.0;
  Eigen::Matrix<double, kDim, 1> gradient;    // Psi_i
  Eigen::Matrix<double, kDim, kDim> hessian;  // Psi_ij
  // Per pair i < j in the order (0,1), (0,2), (1,2) (PairFirst, PairSecond).
  double twist[kPairs] = {};
  double flip[kPairs] = {};
};

// The pair p = 0, 1, 2 as (i, j), i < j: (0,1), (0,2), (1,2).
constexpr int PairFirst(int p) { return p < 2 ? 0 : 1; }
constexpr int PairSecond(int p) { return p < 1 ? 1 : 2; }

// J / (sigma_i sigma_j) for i != j without dividing: the product of the other
// singular values.
template <int kDim>
double OtherProduct(const Eigen::Matrix<double, kDim, 1>& sigma, int i, int j) {
  if constexpr (kDim == 2) {
    return 1.0;
  } else {
    return sigma[3 - i - j];
  }
}

// s: the singular values, all > 0 (not checked; the caller checks that the
// results are finite). False for the linear model. Hessian, twist and flip
// only with `hessian`.
template <int kDim>
bool EvaluateSingularValueEnergy(ElasticModel model, const Eigen::Matrix<double, kDim, 1>& s,
                                 double mu, double lambda, bool hessian,
                                 SingularValueEnergy<kDim>* out) {
  constexpr int kPairs = SingularValueEnergy<kDim>::kPairs;
  const double J = s.prod();
  if (model == ElasticModel::kNeoHookean) {
    const double log_j = std::log(J);
    const double a = lambda * log_j - mu;  // Psi_i = mu s_i + a / s_i
    out->psi = 0.5 * mu * (s.squaredNorm() - kDim) - mu * log_j + 0.5 * lambda * log_j * log_j;
    for (int i = 0; i < kDim; ++i) out->gradient[i] = mu * s[i] + a / s[i];
    if (!hessian) return true;
    for (int i = 0; i < kDim; ++i) {
      for (int j = 0; j < kDim; ++j) {
        out->hessian(i, j) = i == j ? mu + (lambda - a) / (s[i] * s[i]) : lambda / (s[i] * s[j]);
      }
    }
    for (int p = 0; p < kPairs; ++p) {
      const double inverse = 1.0 / (s[PairFirst(p)] * s[PairSecond(p)]);
      out->twist[p] = mu + a * inverse;
      out->flip[p] = mu - a * inverse;
    }
  } else if (model == ElasticModel::kStvk) {
    double T = 0.0, shear = 0.0;
    for (int k = 0; k < kDim; ++k) {
      const double e = s[k] * s[k] - 1.0;
      T += 0.5 * e;
      shear += e * e;
    }
    out->psi = 0.25 * mu * shear + 0.5 * lambda * T * T;
    for (int i = 0; i < kDim; ++i)
      out->gradient[i] = (mu * (s[i] * s[i] - 1.0) + lambda * T) * s[i];
    if (!hessian) return true;
    for (int i = 0; i < kDim; ++i) {
      for (int j = 0; j < kDim; ++j) {
        out->hessian(i, j) = i == j ? mu * (3.0 * s[i] * s[i] - 1.0) + lambda * (T + s[i] * s[i])
                                    : lambda * s[i] * s[j];
      }
    }
    for (int p = 0; p < kPairs; ++p) {
      const double si = s[PairFirst(p)], sj = s[PairSecond(p)];
      const double squares = si * si + sj * sj - 1.0;
      out->twist[p] = lambda * T + mu * (squares - si * sj);
      out->flip[p] = lambda * T + mu * (squares + si * sj);
    }
  } else if (model == ElasticModel::kFixedCorotated) {
    out->psi = mu * (s.array() - 1.0).square().sum() + 0.5 * lambda * (J - 1.0) * (J - 1.0);
    // g_i = J / s_i as the product of the others (exact for any s_i > 0).
    Eigen::Matrix<double, kDim, 1> g;
    for (int i = 0; i < kDim; ++i) {
      g[i] = 1.0;
      for (int k = 0; k < kDim; ++k) {
        if (k != i) g[i] *= s[k];
      }
      out->gradient[i] = 2.0 * mu * (s[i] - 1.0) + lambda * (J - 1.0) * g[i];
    }
    if (!hessian) return true;
    for (int i = 0; i < kDim; ++i) {
      for (int j = 0; j < kDim; ++j) {
        out->hessian(i, j) = i == j ? 2.0 * mu + lambda * g[i] * g[i]
                                    : lambda * (2.0 * J - 1.0) * OtherProduct<kDim>(s, i, j);
      }
    }
    for (int p = 0; p < kPairs; ++p) {
      const int i = PairFirst(p), j = PairSecond(p);
      const double bulk = lambda * (J - 1.0) * OtherProduct<kDim>(s, i, j);
      out->twist[p] = 2.0 * mu * (1.0 - 2.0 / (s[i] + s[j])) + bulk;
      out->flip[p] = 2.0 * mu - bulk;
    }
  } else {
    return false;
  }
  return true;
}

}  // namespace ipstep

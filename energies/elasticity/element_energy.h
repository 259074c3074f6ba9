// The elastic energy of one linear element (triangle in 2D, tetrahedron in
// 3D) as a Ceres autodiff functor: e = V Psi(F), V the rest area/volume, F the
// (constant) deformation gradient
//   F = Ds Dm^{-1},  Ds = [x1 - x0, ..., xd - x0],  Dm the same at rest,
// J = det F = det Ds / det Dm (> 0 at rest: meshes are positively oriented).
//
// How the energy becomes a residual (e = 1/2 rho(|r|^2), core/term.h):
//
// * linear, stvk, fixed_corotated are sums of squares, so r is exact and
//   smooth, with no loss: with the strain G (eps = sym(F) - I for linear,
//   E = (F^T F - I)/2 for stvk) and its deviator dev G = G - tr(G)/d I,
//     mu |G|^2 + lambda/2 tr(G)^2 = mu |dev G|^2 + K/2 tr(G)^2,  K = lambda + 2 mu/d,
//   so r = [sqrt(2 mu V) dev G_ii (d entries), sqrt(4 mu V) G_ij (i < j),
//   sqrt(K V) tr G]: d(d+1)/2 + 1 residuals. The deviatoric split keeps every
//   coefficient positive for every nu in (-1, 1/2) (K > 0 there; lambda itself
//   is negative for nu < 0). fixed_corotated: r = [sqrt(2 mu V) (F - R)_ij
//   (d^2 entries), sqrt(lambda V) (J - 1)], which needs lambda >= 0 (nu >= 0;
//   the scene loader says so). The Gauss-Newton model J^T J of these residuals
//   is PSD, the Newton model (core/term_hessian.h) adds sum r_k Hess r_k,
//   analytic for stvk and 2D fixed_corotated (Curvature below,
//   element_curvature.h), by central differences of the autodiff Jacobian for
//   3D fixed_corotated; linear's residuals are affine, so J^T J is its exact
//   Hessian (kGaussNewtonModel).
// * neo_hookean is not a sum of squares (mu/2 (|F|^2 - d) - mu ln J vanishes
//   quadratically on the rotations, so sqrt(2 V Psi) has a kink there). It uses
//   one residual r = sqrt(2 V Psi + c) with a constant c = 1e-4 mu V > 0, smooth as
//   long as 2 V Psi + c > 0, and the loss rho(s) = s - c (OffsetLoss: rho' = 1,
//   rho'' = 0, so Ceres's corrector is the identity), which gives back
//   1/2 rho(r^2) = V Psi exactly. Its Newton model is exact (r J^T = grad e and
//   J^T J + r Hess r = Hess e, Hess r analytic: element_curvature.h); its
//   Gauss-Newton model is only rank one. The
//   price is precision: e is the difference of r^2 / 2 and c / 2, about
//   1e-20 mu V absolute in double, i.e. a relative error of 1e-20 / strain^2
//   per element (the extended-precision line-search energy is V Psi itself,
//   in long double, with no offset: Term::precise_energy). (With
//   nu < 0, lambda < 0 and Psi is unbounded below as J -> 0; the term fails
//   where 2 V Psi + c <= 0.)
//
// Every model fails the evaluation (returns false) where J <= 0: an inverted
// element is outside the domain, the trust region rejects such a trial point
// and the step filter (inversion_filter.h) keeps steps away from it.
#pragma once

#include <cmath>

#include <Eigen/Core>

#include "core/term_hessian.h"
#include "energies/elasticity/element_curvature.h"
#include "energies/elasticity/isotropic_eigensystem.h"
#include "energies/elasticity/polar_decomposition.h"
#include "problems/elastic_material.h"

namespace ipstep {

// c / (mu V) of the neo-Hookean residual (below). Smaller keeps more digits of
// the energy (its absolute round-off is about 1e-16 c); larger keeps r smooth
// on a wider scale (r = sqrt(2 V Psi + c) bends where V Psi ~ c, i.e. at
// strains ~ sqrt(c / (mu V)) = 1e-2 here, far above the central-difference
// step of the Newton model). Measured on cantilever_2d with Newmark and
// lbfgs: with 1 the line search stalled at 1.0e-5 m/s on 32 of 100 steps, with
// 1e-4 (fixed_corotated and stvk, exact squares, never stalled).
constexpr double kNeoHookeanOffset = 1e-4;

// True for the models whose Newton model is the closed-form reduced one
// (isotropic_eigensystem.h): every isotropic model, not linear (whose
// Gauss-Newton model is already its exact Hessian).
constexpr bool HasReducedModel(ElasticModel model) { return model != ElasticModel::kLinear; }

template <ElasticModel kModel, int kDim>
struct ElasticElement {
  static constexpr int kResiduals = kModel == ElasticModel::kNeoHookean ? 1
                                    : kModel == ElasticModel::kFixedCorotated
                                        ? kDim * kDim + 1
                                        : kDim * (kDim + 1) / 2 + 1;
  static constexpr bool kGaussNewtonModel = kModel == ElasticModel::kLinear;

  // rest: kDim + 1 node positions (kDim each), positively oriented.
  ElasticElement(const double* const* rest, double mu, double lambda) : mu(mu), lambda(lambda) {
    for (int c = 0; c < kDim; ++c) {
      for (int k = 0; k < kDim; ++k) dm[k][c] = rest[c + 1][k] - rest[0][k];
    }
    double det;
    if constexpr (kDim == 2) {
      det = dm[0][0] * dm[1][1] - dm[0][1] * dm[1][0];
      dm_inv[0][0] = dm[1][1] / det;
      dm_inv[0][1] = -dm[0][1] / det;
      dm_inv[1][0] = -dm[1][0] / det;
      dm_inv[1][1] = dm[0][0] / det;
      volume = 0.5 * det;
    } else {
      det = Determinant3(dm);
      double inv_t[3][3];
      InverseTranspose3(dm, inv_t);
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) dm_inv[i][j] = inv_t[j][i];
      }
      volume = det / 6.0;
    }
    offset = kNeoHookeanOffset * mu * volume;
  }

  template <typename T>
  bool operator()(const T* x0, const T* x1, const T* x2, T* r) const {
    const T* x[3] = {x0, x1, x2};
    return Residuals(x, r);
  }
  template <typename T>
  bool operator()(const T* x0, const T* x1, const T* x2, const T* x3, T* r) const {
    const T* x[4] = {x0, x1, x2, x3};
    return Residuals(x, r);
  }

  // F = Ds Dm^{-1}; returns J = det F.
  template <typename T>
  T DeformationGradient(const T* const* x, T F[kDim][kDim]) const {
    T ds[kDim][kDim];
    for (int c = 0; c < kDim; ++c) {
      for (int k = 0; k < kDim; ++k) ds[k][c] = x[c + 1][k] - x[0][k];
    }
    for (int i = 0; i < kDim; ++i) {
      for (int j = 0; j < kDim; ++j) {
        F[i][j] = T(0.0);
        for (int k = 0; k < kDim; ++k) F[i][j] += ds[i][k] * dm_inv[k][j];
      }
    }
    if constexpr (kDim == 2) {
      return F[0][0] * F[1][1] - F[0][1] * F[1][0];
    } else {
      return Determinant3(F);
    }
  }

  template <typename T>
  bool Residuals(const T* const* x, T* r) const {
    using std::log;
    using std::sqrt;
    T F[kDim][kDim];
    const T J = DeformationGradient(x, F);
    if (!(J > 0.0)) return false;
    if constexpr (kModel == ElasticModel::kLinear || kModel == ElasticModel::kStvk) {
      T G[kDim][kDim];
      for (int i = 0; i < kDim; ++i) {
        for (int j = 0; j < kDim; ++j) {
          if constexpr (kModel == ElasticModel::kLinear) {
            G[i][j] = 0.5 * (F[i][j] + F[j][i]);
          } else {
            G[i][j] = T(0.0);
            for (int k = 0; k < kDim; ++k) G[i][j] += F[k][i] * F[k][j];
            G[i][j] *= 0.5;
          }
          if (i == j) G[i][j] -= 0.5 * (kModel == ElasticModel::kLinear ? 2.0 : 1.0);
        }
      }
      T trace(0.0);
      for (int i = 0; i < kDim; ++i) trace += G[i][i];
      const double diagonal = std::sqrt(2.0 * mu * volume);
      const double off_diagonal = std::sqrt(4.0 * mu * volume);
      const double bulk = std::sqrt((lambda + 2.0 * mu / kDim) * volume);
      int n = 0;
      for (int i = 0; i < kDim; ++i) r[n++] = diagonal * (G[i][i] - trace / double(kDim));
      for (int i = 0; i < kDim; ++i) {
        for (int j = i + 1; j < kDim; ++j) r[n++] = off_diagonal * G[i][j];
      }
      r[n] = bulk * trace;
      return true;
    } else if constexpr (kModel == ElasticModel::kFixedCorotated) {
      T R[kDim][kDim];
      if constexpr (kDim == 2) {
        PolarRotation2(F, R);
      } else {
        if (!PolarRotation3(F, R)) return false;
      }
      const double shear = std::sqrt(2.0 * mu * volume);
      for (int i = 0; i < kDim; ++i) {
        for (int j = 0; j < kDim; ++j) r[kDim * i + j] = shear * (F[i][j] - R[i][j]);
      }
      r[kDim * kDim] = std::sqrt(lambda * volume) * (J - 1.0);
      return true;
    } else {
      T norm2(0.0);
      for (int i = 0; i < kDim; ++i) {
        for (int j = 0; j < kDim; ++j) norm2 += F[i][j] * F[i][j];
      }
      const T log_j = log(J);
      const T psi = 0.5 * mu * (norm2 - double(kDim)) - mu * log_j + 0.5 * lambda * log_j * log_j;
      const T s = 2.0 * volume * psi + offset;
      if (!(s > 0.0)) return false;
      r[0] = sqrt(s);
      return true;
    }
  }

  // Term::precise_energy (core/term.h): V Psi in long double, without the
  // neo-Hookean offset and without cancellation. Near rest Psi is O(strain^2)
  // while its parts |F|^2 - d and ln J are O(1) and O(strain): summing those
  // (even in long double) leaves noise of about 1e-19 mu V per element, which
  // on 1.6e5 tetrahedra hid the last Newton decrease of a backward-Euler step
  // (2e-19 J of noise against 2e-20 J of decrease: the line search stalled at
  // 2.8e-5 m/s). So Psi is written in the displacement gradient
  // H = F - I = (Ds - Dm) Dm^{-1} (exact differences) with q = J - 1 =
  // tr H + I2(H) + det H (3D; tr H + det H in 2D), I2 = (tr^2 H - tr H^2)/2:
  //   |F|^2 - d = 2 tr H + |H|^2,   tr H - ln J = -(I2 + det H) + (q - log1p q),
  //   Psi = mu/2 |H|^2 - mu (I2 + det H) + mu (q - log1p q) + lambda/2 log1p(q)^2,
  // every part O(strain^2).
  bool PreciseEnergy(const double* const* x, long double* energy) const {
    static_assert(kModel == ElasticModel::kNeoHookean);
    long double h[kDim][kDim];
    for (int i = 0; i < kDim; ++i) {
      for (int j = 0; j < kDim; ++j) {
        long double sum = 0.0L;
        for (int c = 0; c < kDim; ++c) {
          const long double edge = (static_cast<long double>(x[c + 1][i]) - x[0][i]) -
                                   static_cast<long double>(dm[i][c]);
          sum += edge * dm_inv[c][j];
        }
        h[i][j] = sum;
      }
    }
    long double trace = 0.0L, norm2 = 0.0L, trace_h2 = 0.0L;
    for (int i = 0; i < kDim; ++i) {
      trace += h[i][i];
      for (int j = 0; j < kDim; ++j) {
        norm2 += h[i][j] * h[i][j];
        trace_h2 += h[i][j] * h[j][i];
      }
    }
    long double det;
    if constexpr (kDim == 2) {
      det = h[0][0] * h[1][1] - h[0][1] * h[1][0];
    } else {
      det = h[0][0] * (h[1][1] * h[2][2] - h[1][2] * h[2][1]) -
            h[0][1] * (h[1][0] * h[2][2] - h[1][2] * h[2][0]) +
            h[0][2] * (h[1][0] * h[2][1] - h[1][1] * h[2][0]);
    }
    const long double i2 = kDim == 3 ? 0.5L * (trace * trace - trace_h2) : 0.0L;
    const long double q = trace + i2 + det;  // J - 1
    if (!(q > -1.0L)) return false;
    const long double log_j = std::log1p(q);
    const long double psi =
        0.5L * mu * norm2 - mu * (i2 + det) + mu * (q - log_j) + 0.5L * lambda * log_j * log_j;
    *energy = volume * psi;
    return std::isfinite(static_cast<double>(*energy));
  }

  // Term::curvature (core/term.h): sum_k c_k Hess r_k over the element's
  // coordinates, row-major; for the models of HasAnalyticCurvature only.
  bool Curvature(const double* const* x, const double* c, double* curvature) const {
    static_assert(HasAnalyticCurvature(kModel, kDim));
    if constexpr (kModel == ElasticModel::kNeoHookean) {
      return element_curvature::NeoHookean<kDim>(x, dm_inv, volume, mu, lambda, offset, c[0],
                                                 curvature);
    } else if constexpr (kModel == ElasticModel::kStvk) {
      return element_curvature::Stvk<kDim>(x, dm_inv, volume, mu, lambda, c, curvature);
    } else {
      return element_curvature::FixedCorotated2(x, dm_inv, volume, mu, lambda, c, curvature);
    }
  }

  // Term::reduced_model (core/term_hessian.h): the energy V Psi(F) through
  // y = vec(F) = B x, B[(i d + j), (a d + k)] = d_ik D_aj (element_curvature.h's
  // (1)), with Psi's F-space eigensystem in closed form
  // (isotropic_eigensystem.h); for the models of HasReducedModel only.
  bool FillReducedModel(const double* const* x, ReducedModel* out) const {
    static_assert(HasReducedModel(kModel));
    double F[kDim][kDim];
    const double J = DeformationGradient(x, F);
    if (!(J > 0.0)) return false;
    Eigen::Matrix<double, kDim, kDim> f;
    for (int i = 0; i < kDim; ++i) {
      for (int j = 0; j < kDim; ++j) f(i, j) = F[i][j];
    }
    DeformationModel<kDim> d;
    if (!IsotropicDeformationModel<kDim>(kModel, f, mu, lambda, true, &d)) return false;
    out->energy = volume * d.psi;
    out->gradient = volume * d.stress;
    out->eigenvalues = volume * d.eigenvalues;
    out->eigenvectors = d.eigenvectors;
    out->map.setZero(kDim * kDim, (kDim + 1) * kDim);
    for (int a = 0; a <= kDim; ++a) {
      for (int j = 0; j < kDim; ++j) {
        double shape = 0.0;  // D_aj
        if (a > 0) {
          shape = dm_inv[a - 1][j];
        } else {
          for (int c = 0; c < kDim; ++c) shape -= dm_inv[c][j];
        }
        for (int i = 0; i < kDim; ++i) out->map(i * kDim + j, a * kDim + i) = shape;
      }
    }
    return true;
  }

  double dm[kDim][kDim];  // rest edges Dm (columns x_c+1 - x_0)
  double dm_inv[kDim][kDim];
  double volume = 0.0;
  double mu = 0.0;
  double lambda = 0.0;
  double offset = 0.0;  // c of the neo-Hookean residual
};

}  // namespace ipstep

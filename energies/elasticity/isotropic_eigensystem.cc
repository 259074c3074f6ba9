#include "energies/elasticity/isotropic_eigensystem.h"

#include <cmath>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>

#include "energies/elasticity/singular_value_energy.h"

namespace ipstep {
namespace {

// F = U diag(sigma) V^T with det U = det V = 1 and sigma > 0; false if F's
// rounded SVD does not give that (det U det V = -1 or a sigma <= 0 despite
// det F > 0, which needs sigma_min ~ 1e-16 sigma_max).
template <int kDim>
bool RotationVariantSvd(const Eigen::Matrix<double, kDim, kDim>& F,
                        Eigen::Matrix<double, kDim, kDim>* U, Eigen::Matrix<double, kDim, 1>* sigma,
                        Eigen::Matrix<double, kDim, kDim>* V) {
  // Square: no QR preconditioner needed.
  const Eigen::JacobiSVD<Eigen::Matrix<double, kDim, kDim>, Eigen::NoQRPreconditioner> svd(
      F, Eigen::ComputeFullU | Eigen::ComputeFullV);
  // (Not Success only for a non-finite F, which leaves the factors unset.)
  if (svd.info() != Eigen::Success) return false;
  *U = svd.matrixU();
  *V = svd.matrixV();
  *sigma = svd.singularValues();
  // det U det V = sign(det F) = 1 (sigma >= 0). If both are -1, negating the
  // same column of both keeps U diag(sigma) V^T and makes them rotations (the
  // modes need only U diag(sigma) V^T = F with sigma > 0; rotations are the
  // paper's convention).
  const bool flip_u = U->determinant() < 0.0, flip_v = V->determinant() < 0.0;
  if (flip_u != flip_v) return false;
  if (flip_u) {
    U->col(kDim - 1) *= -1.0;
    V->col(kDim - 1) *= -1.0;
  }
  return sigma->minCoeff() > 0.0;
}

// vec(U B V^T) for B = sum_k z_k e_k e_k^T (z a d-vector) and for
// B = (e_i e_j^T + sign e_j e_i^T) / sqrt(2).
template <int kDim>
void Scaling(const Eigen::Matrix<double, kDim, kDim>& U, const Eigen::Matrix<double, kDim, kDim>& V,
             const Eigen::Matrix<double, kDim, 1>& z, double* q) {
  for (int a = 0; a < kDim; ++a) {
    for (int b = 0; b < kDim; ++b) {
      double sum = 0.0;
      for (int k = 0; k < kDim; ++k) sum += z[k] * U(a, k) * V(b, k);
      q[a * kDim + b] = sum;
    }
  }
}

template <int kDim>
void Pair(const Eigen::Matrix<double, kDim, kDim>& U, const Eigen::Matrix<double, kDim, kDim>& V,
          int i, int j, double sign, double* q) {
  const double scale = std::sqrt(0.5);
  for (int a = 0; a < kDim; ++a) {
    for (int b = 0; b < kDim; ++b) {
      q[a * kDim + b] = scale * (U(a, i) * V(b, j) + sign * U(a, j) * V(b, i));
    }
  }
}

}  // namespace

template <int kDim>
bool IsotropicDeformationModel(ElasticModel model, const Eigen::Matrix<double, kDim, kDim>& F,
                               double mu, double lambda, bool hessian,
                               DeformationModel<kDim>* out) {
  using Matrix = Eigen::Matrix<double, kDim, kDim>;
  constexpr int kPairs = SingularValueEnergy<kDim>::kPairs;
  if (model == ElasticModel::kLinear || !F.allFinite() || !(F.determinant() > 0.0)) return false;
  Matrix U, V;
  Eigen::Matrix<double, kDim, 1> sigma;
  if (!RotationVariantSvd<kDim>(F, &U, &sigma, &V)) return false;
  SingularValueEnergy<kDim> s;
  if (!EvaluateSingularValueEnergy<kDim>(model, sigma, mu, lambda, hessian, &s)) return false;
  out->psi = s.psi;
  Scaling<kDim>(U, V, s.gradient, out->stress.data());
  if (!std::isfinite(out->psi) || !out->stress.allFinite()) return false;
  if (!hessian) return true;

  // Scaling modes: d columns; then per pair a twist and a flip.
  const Eigen::SelfAdjointEigenSolver<Matrix> scaling(s.hessian);
  if (scaling.info() != Eigen::Success) return false;
  for (int k = 0; k < kDim; ++k) {
    out->eigenvalues[k] = scaling.eigenvalues()[k];
    const Eigen::Matrix<double, kDim, 1> z = scaling.eigenvectors().col(k);
    Scaling<kDim>(U, V, z, out->eigenvectors.col(k).data());
  }
  for (int p = 0; p < kPairs; ++p) {
    const int twist = kDim + 2 * p, flip = twist + 1;
    const int i = PairFirst(p), j = PairSecond(p);
    out->eigenvalues[twist] = s.twist[p];
    out->eigenvalues[flip] = s.flip[p];
    Pair<kDim>(U, V, i, j, -1.0, out->eigenvectors.col(twist).data());
    Pair<kDim>(U, V, i, j, 1.0, out->eigenvectors.col(flip).data());
  }
  return out->eigenvalues.allFinite();
}

template bool IsotropicDeformationModel<2>(ElasticModel, const Eigen::Matrix2d&, double, double,
                                           bool, DeformationModel<2>*);
template bool IsotropicDeformationModel<3>(ElasticModel, const Eigen::Matrix3d&, double, double,
                                           bool, DeformationModel<3>*);

}  // namespace ipstep

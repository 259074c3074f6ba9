// The energy density of an isotropic elastic model (element_energy.h:
// neo_hookean, stvk, fixed_corotated) at one deformation gradient F, with its
// stress P = dPsi/dF and the eigensystem of the F-space Hessian
// A = d2Psi/dF2 in closed form (Smith, de Goes, Kim, "Analytic Eigensystems
// for Isotropic Distortion Energies", ACM TOG 2019; the block diagonalisation
// of Teran et al. 2005).
//
// Every isotropic Psi is a function psi(sigma) of the singular values of the
// rotation-variant SVD F = U diag(sigma) V^T (det U = det V = 1; sigma > 0
// for J > 0). The matrices U B V^T, B running over the unit matrices e_i e_j^T,
// are an orthonormal basis of F-space (Frobenius), and in it
//   P = U diag(Psi_i) V^T,
// and A splits into one d x d block on the diagonal matrices (the sigma
// Hessian Psi_ij) and one 2 x 2 block per pair i < j on the coordinates
// b_ij, b_ji of B. Along dF = U dB V^T, with dU = U W and dV = V W' (W, W'
// skew), the SVD's differential gives dB_ij = W_ij s_j - s_i W'_ij (i != j)
// and (U^T dP V)_ij = W_ij Psi_j - Psi_i W'_ij; eliminating W_ij and W'_ij,
//   (U^T dP V)_ij = [(Psi_i s_i - Psi_j s_j) dB_ij + (Psi_i s_j - Psi_j s_i) dB_ji]
//                   / (s_i^2 - s_j^2),
// a symmetric 2 x 2 block whose eigenvectors are dB_ji = -dB_ij and
// dB_ji = dB_ij:
//   twist Q = U (e_i e_j^T - e_j e_i^T) V^T / sqrt(2), eigenvalue (Psi_i + Psi_j) / (s_i + s_j),
//   flip  Q = U (e_i e_j^T + e_j e_i^T) V^T / sqrt(2), eigenvalue (Psi_i - Psi_j) / (s_i - s_j),
// and the scaling modes Q = U diag(z) V^T, z the unit eigenvectors of Psi_ij.
// d + d(d - 1) = d^2 orthonormal eigenvectors in all. The per-energy closed
// forms of Psi_i, Psi_ij, twist and flip (none divides by s_i - s_j) and their
// derivations are in singular_value_energy.h.
//
// vec(M)[i * kDim + j] = M(i, j): row-major, the order of element_energy.h's
// F[i][j]. An element with F = Ds Dm^{-1} maps these to its coordinates by
// element_curvature.h's (1): dF_ij = sum_a dx_(a,i) D_aj.
#pragma once

#include <Eigen/Core>

#include "problems/elastic_material.h"

namespace ipstep {

// F-space model of one energy density.
template <int kDim>
struct DeformationModel {
  static constexpr int kSize = kDim * kDim;
  double psi = 0.0;                        // energy density
  Eigen::Matrix<double, kSize, 1> stress;  // vec(P), P = dPsi/dF
  // Of A = d2Psi/dF2 (vec x vec), in no promised order (now: the d scaling
  // modes, then per pair (0,1), (0,2), (1,2) its twist and its flip).
  Eigen::Matrix<double, kSize, 1> eigenvalues;
  // Columns vec(Q_k), orthonormal: A = Q diag(eigenvalues) Q^T.
  Eigen::Matrix<double, kSize, kSize> eigenvectors;
};

// kDim = 2 or 3; model neo_hookean, stvk or fixed_corotated (false for
// linear). False where J = det F <= 0 or the result is not finite. With
// `hessian` false only psi and stress are set.
template <int kDim>
bool IsotropicDeformationModel(ElasticModel model, const Eigen::Matrix<double, kDim, kDim>& F,
                               double mu, double lambda, bool hessian, DeformationModel<kDim>* out);

extern template bool IsotropicDeformationModel<2>(ElasticModel, const Eigen::Matrix2d&, double,
                                                  double, bool, DeformationModel<2>*);
extern template bool IsotropicDeformationModel<3>(ElasticModel, const Eigen::Matrix3d&, double,
                                                  double, bool, DeformationModel<3>*);

}  // namespace ipstep

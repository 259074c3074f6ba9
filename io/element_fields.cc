#include "io/element_fields.h"

#include <cmath>
#include <limits>

#include <Eigen/LU>

#include "energies/elasticity/isotropic_eigensystem.h"

namespace ipstep {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

template <int kDim>
using Matrix = Eigen::Matrix<double, kDim, kDim>;

// The neo-Hookean Psi in the displacement gradient H = F - I (element_energy.h's
// PreciseEnergy): every part O(strain^2), so that Psi near rest is not the
// round-off of O(1) parts (it would come out negative there).
template <int kDim>
double NeoHookeanPsi(const Matrix<kDim>& H, double mu, double lambda) {
  const double trace = H.trace();
  const double i2 = kDim == 3 ? 0.5 * (trace * trace - (H * H).trace()) : 0.0;
  const double q = trace + i2 + H.determinant();  // J - 1
  const double log_j = std::log1p(q);
  return 0.5 * mu * H.squaredNorm() - mu * (i2 + H.determinant()) + mu * (q - log_j) +
         0.5 * lambda * log_j * log_j;
}

// Psi and the Cauchy stress at F = I + H; false where the model is not
// defined.
template <int kDim>
bool EnergyAndStress(const ElasticMaterial& material, const Matrix<kDim>& H, double* psi,
                     Matrix<kDim>* cauchy) {
  const Matrix<kDim> F = Matrix<kDim>::Identity() + H;
  const double mu = material.mu(), lambda = material.lambda(kDim);
  const double J = F.determinant();
  if (!(J > 0.0)) return false;
  if (material.model == ElasticModel::kLinear) {
    const Matrix<kDim> eps = 0.5 * (F + F.transpose()) - Matrix<kDim>::Identity();
    const double trace = eps.trace();
    *psi = mu * eps.squaredNorm() + 0.5 * lambda * trace * trace;
    *cauchy = 2.0 * mu * eps + lambda * trace * Matrix<kDim>::Identity();
    return true;
  }
  DeformationModel<kDim> model;
  if (!IsotropicDeformationModel<kDim>(material.model, F, mu, lambda, false, &model)) return false;
  Matrix<kDim> P;
  for (int i = 0; i < kDim; ++i) {
    for (int j = 0; j < kDim; ++j) P(i, j) = model.stress[i * kDim + j];
  }
  *psi =
      material.model == ElasticModel::kNeoHookean ? NeoHookeanPsi<kDim>(H, mu, lambda) : model.psi;
  *cauchy = P * F.transpose() / J;
  return true;
}

double VonMises(const Eigen::Matrix2d& s) {
  return std::sqrt(s(0, 0) * s(0, 0) - s(0, 0) * s(1, 1) + s(1, 1) * s(1, 1) +
                   3.0 * s(0, 1) * s(1, 0));
}

double VonMises(const Eigen::Matrix3d& s) {
  const Eigen::Matrix3d deviator = s - s.trace() / 3.0 * Eigen::Matrix3d::Identity();
  return std::sqrt(1.5 * deviator.squaredNorm());
}

template <int kDim>
ElementFields Fields(const Solid& solid, const Eigen::VectorXd& x) {
  const SimplexMesh& mesh = solid.mesh;
  ElementFields fields;
  for (const std::array<int, 4>& e : mesh.elements) {
    Matrix<kDim> rest, change;  // Dm, Ds - Dm (exact differences)
    for (int c = 0; c < kDim; ++c) {
      for (int k = 0; k < kDim; ++k) {
        rest(k, c) = mesh.positions[kDim * e[c + 1] + k] - mesh.positions[kDim * e[0] + k];
        change(k, c) = (x[kDim * e[c + 1] + k] - x[kDim * e[0] + k]) - rest(k, c);
      }
    }
    const Matrix<kDim> H = change * rest.inverse();  // F - I
    double psi = kNaN;
    Matrix<kDim> cauchy;
    const bool defined = EnergyAndStress<kDim>(solid.material, H, &psi, &cauchy);
    fields.J.push_back((Matrix<kDim>::Identity() + H).determinant());
    fields.energy_density.push_back(defined ? psi : kNaN);
    fields.von_mises_stress.push_back(defined ? VonMises(cauchy) : kNaN);
  }
  return fields;
}

}  // namespace

ElementFields SolidElementFields(const Solid& solid, const Eigen::VectorXd& x) {
  return solid.mesh.dimension == 2 ? Fields<2>(solid, x) : Fields<3>(solid, x);
}

}  // namespace ipstep

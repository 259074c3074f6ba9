// Material of an elastic solid: the energy density model and its constants.
//
//   mu = E / (2 (1 + nu)),   lambda = E nu / ((1 + nu)(1 - 2 nu))   (Lame constants)
//
// 2D elements are plane strain by default (a slice of an infinitely thick
// body: the out-of-plane strain is zero and the constants above apply
// unchanged). Plane stress (a thin sheet: the out-of-plane stress is zero)
// eliminates the out-of-plane strain of the small-strain law, which leaves the
// same in-plane law with the effective
//   lambda* = 2 mu lambda / (lambda + 2 mu)   (= E nu / (1 - nu^2)),
// used here for every model (for the nonlinear ones it is the usual
// approximation, exact in the small-strain limit).
#pragma once

#include <string>

namespace ipstep {

enum class ElasticModel {
  kLinear,          // small strain: mu |eps|^2 + lambda/2 tr(eps)^2, eps = sym(F) - I
  kStvk,            // St. Venant-Kirchhoff: mu |E|^2 + lambda/2 tr(E)^2, E = (F^T F - I)/2
  kFixedCorotated,  // mu |F - R|^2 + lambda/2 (J - 1)^2, F = R S (polar decomposition)
  kNeoHookean,      // mu/2 (tr(F^T F) - d) - mu ln J + lambda/2 (ln J)^2
};

// "linear", "stvk", "fixed_corotated", "neo_hookean".
const char* ElasticModelName(ElasticModel model);
// False for an unknown name.
bool ParseElasticModel(const std::string& name, ElasticModel* model);

// How a solid's mass is given to its nodes: lumped (each element gives
// density * measure / (d + 1) to each of its nodes) or uniform (every node
// the body's total mass / node count, as the course code's section 6 does).
enum class MassDistribution { kLumped, kUniform };

// "lumped", "uniform".
const char* MassDistributionName(MassDistribution masses);
// False for an unknown name.
bool ParseMassDistribution(const std::string& name, MassDistribution* masses);

struct ElasticMaterial {
  ElasticModel model = ElasticModel::kNeoHookean;
  double youngs_modulus = 1e5;  // E [Pa]
  double poisson_ratio = 0.3;   // nu, in (-1, 0.5)
  double density = 1000.0;      // rho [kg/m^d]: kg/m^2 in 2D (per unit thickness), kg/m^3 in 3D
  bool plane_stress = false;    // 2D only
  MassDistribution masses = MassDistribution::kLumped;

  double mu() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }
  // lambda, or lambda* for plane stress in 2D.
  double lambda(int dimension) const {
    const double nu = poisson_ratio;
    const double l = youngs_modulus * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    if (dimension == 2 && plane_stress) return 2.0 * mu() * l / (l + 2.0 * mu());
    return l;
  }
};

}  // namespace ipstep

// Per-element fields of an elastic solid at positions x, for the frames
// (io/frame_writer.h): with F = Ds Dm^{-1} the element's deformation gradient
// (energies/elasticity/element_energy.h),
//   J                   det F (volume ratio; <= 0 for an inverted element),
//   energy_density      Psi(F) of the solid's model [J/m^3 = Pa] (per unit rest
//                       volume; a 2D solid's per unit rest area and thickness),
//   von_mises_stress    of the Cauchy stress sigma = P F^T / J, P = dPsi/dF
//                       (linear: the small-strain stress 2 mu eps + lambda
//                       tr(eps) I) [Pa]: sqrt(3/2 |dev sigma|^2) in 3D; in 2D
//                       sqrt(s_xx^2 - s_xx s_yy + s_yy^2 + 3 s_xy^2), the
//                       in-plane stress with s_zz = 0 (exact for plane stress;
//                       under plane strain it leaves s_zz out).
// Psi and the stress are NaN where the model is not defined (J <= 0).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "problems/solid.h"

namespace ipstep {

struct ElementFields {
  std::vector<double> J, energy_density, von_mises_stress;  // per element
};

// x: the scene's coordinates, `dimension` per node (the solid's nodes are the
// scene's first nodes, in order).
ElementFields SolidElementFields(const Solid& solid, const Eigen::VectorXd& x);

}  // namespace ipstep

// Keeps every element of an elastic solid positively oriented (J > 0): the
// step filter (core/step_filter.h) of the "elasticity" effect.
//
// Along a straight path x(t) = a + t (b - a), every edge vector of an element
// is affine in t, so det Ds(t) is a polynomial of degree d in t (quadratic in
// 2D, cubic in 3D):
//   2D: det(A + t B) = det A + t (a00 b11 + b00 a11 - a01 b10 - b01 a10) + t^2 det B,
//   3D: det(A + t B) = det A + t tr(adj(A) B) + t^2 tr(adj(B) A) + t^3 det B,
// A = Ds(a), B = Ds(b) - Ds(a). MaxStepSize returns the smallest root in
// (0, 1] over all elements (1 if none): the largest step along which no
// element degenerates. The callers (sim/simulation.cc, the solvers) take a
// fraction (0.8-0.9) of it, as IPC-style codes do, so the first trial point
// keeps every J > 0 with a margin. Roots are found robustly, without the
// cubic formula: the polynomial is monotone between the roots of its
// derivative, and the first interval of [0, 1] whose end is <= 0 is bisected
// to full precision.
//
// IsStepValid(x): every element of x positive and no element degenerating on
// the path from the last accepted iterate (Ceres's trial points are vetoed,
// the line searches back off). IsFeasible(x): every element of x positive
// (checked after every step). Diagnostics: "min_J", the smallest det F over
// the elements (1 at rest).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/step_filter.h"

namespace ipstep {

class InversionFilter : public StepFilter {
 public:
  // `elements`: dimension + 1 node indices each; `rest`: positions (dimension per
  // node) at which every element is positively oriented.
  InversionFilter(int dimension, std::vector<std::array<int, 4>> elements,
                  const std::vector<double>& rest);

  void OnAccepted(const double* x) override;
  bool IsStepValid(const double* x) const override;
  double MaxStepSize(const double* from, const double* to) const override;
  bool IsFeasible(const double* x) const override;
  std::vector<std::string> DiagnosticNames() const override { return {"min_J"}; }
  std::vector<double> Diagnostics(const double* x) const override;

  // det F of element e at positions x.
  double VolumeRatio(const double* x, int e) const;
  // The first element with det F <= 0 at x, or -1.
  int FirstInverted(const double* x) const;

 private:
  // det Ds of element e along from + t (to - from): the polynomial's
  // coefficients c[0] + c[1] t + ... + c[dimension] t^dimension.
  void PathPolynomial(const double* from, const double* to, int e, double c[4]) const;

  int dimension_;
  std::vector<std::array<int, 4>> elements_;
  std::vector<double> rest_det_;  // det Dm per element
  std::vector<double> accepted_;  // last accepted iterate
};

// Smallest root in (0, 1] of the polynomial c[0] + ... + c[degree] t^degree
// (degree <= 3) with c[0] > 0, or 1 when it stays positive on [0, 1]; more
// precisely the smallest t where it reaches <= 0.
double FirstNonPositive(const double* c, int degree);

}  // namespace ipstep

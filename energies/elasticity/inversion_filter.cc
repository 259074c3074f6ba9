#include "energies/elasticity/inversion_filter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace ipstep {
namespace {

double Evaluate(const double* c, int degree, double t) {
  double v = c[degree];
  for (int k = degree - 1; k >= 0; --k) v = v * t + c[k];
  return v;
}

double Det2(const double m[3][3]) { return m[0][0] * m[1][1] - m[0][1] * m[1][0]; }

double Det3(const double m[3][3]) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
         m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

// tr(adj(A) B) for 3x3 matrices: the derivative of det at A in direction B,
// sum over columns of det(A with column j replaced by B's column j).
double MixedDet3(const double A[3][3], const double B[3][3]) {
  double sum = 0.0;
  for (int j = 0; j < 3; ++j) {
    double m[3][3];
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) m[r][c] = c == j ? B[r][c] : A[r][c];
    }
    sum += Det3(m);
  }
  return sum;
}

}  // namespace

double FirstNonPositive(const double* c, int degree) {
  // Breakpoints: 0, the roots of the derivative inside (0, 1), 1.
  std::vector<double> points = {0.0};
  const double d1 = c[1], d2 = degree >= 2 ? 2.0 * c[2] : 0.0, d3 = degree >= 3 ? 3.0 * c[3] : 0.0;
  // derivative d1 + d2 t + d3 t^2
  if (d3 != 0.0) {
    const double disc = d2 * d2 - 4.0 * d3 * d1;
    if (disc >= 0.0) {
      const double q = -0.5 * (d2 + std::copysign(std::sqrt(disc), d2));
      if (q != 0.0) points.push_back(q / d3);
      if (q != 0.0) points.push_back(d1 / q);
      if (q == 0.0) points.push_back(0.0);
    }
  } else if (d2 != 0.0) {
    points.push_back(-d1 / d2);
  }
  points.push_back(1.0);
  std::sort(points.begin(), points.end());
  double lo = 0.0;
  for (double p : points) {
    if (!(p > lo) || p > 1.0) continue;
    if (Evaluate(c, degree, p) <= 0.0) {
      // Monotone on [lo, p], positive at lo, <= 0 at p: bisect.
      double a = lo, b = p;
      for (int k = 0; k < 200 && b - a > 0.0; ++k) {
        const double m = 0.5 * (a + b);
        if (m <= a || m >= b) break;
        if (Evaluate(c, degree, m) > 0.0) {
          a = m;
        } else {
          b = m;
        }
      }
      return a;
    }
    lo = p;
  }
  return 1.0;
}

InversionFilter::InversionFilter(int dimension, std::vector<std::array<int, 4>> elements,
                                 const std::vector<double>& rest)
    : dimension_(dimension), elements_(std::move(elements)), accepted_(rest) {
  rest_det_.resize(elements_.size());
  for (size_t e = 0; e < elements_.size(); ++e) {
    double c[4];
    PathPolynomial(rest.data(), rest.data(), static_cast<int>(e), c);
    rest_det_[e] = c[0];
  }
}

void InversionFilter::PathPolynomial(const double* from, const double* to, int e,
                                     double c[4]) const {
  const int d = dimension_;
  const std::array<int, 4>& n = elements_[e];
  double A[3][3], B[3][3];
  for (int col = 0; col < d; ++col) {
    for (int k = 0; k < d; ++k) {
      A[k][col] = from[d * n[col + 1] + k] - from[d * n[0] + k];
      B[k][col] = (to[d * n[col + 1] + k] - to[d * n[0] + k]) - A[k][col];
    }
  }
  if (d == 2) {
    c[0] = Det2(A);
    c[1] = A[0][0] * B[1][1] + B[0][0] * A[1][1] - A[0][1] * B[1][0] - B[0][1] * A[1][0];
    c[2] = Det2(B);
    c[3] = 0.0;
  } else {
    c[0] = Det3(A);
    c[1] = MixedDet3(A, B);
    c[2] = MixedDet3(B, A);
    c[3] = Det3(B);
  }
}

double InversionFilter::VolumeRatio(const double* x, int e) const {
  double c[4];
  PathPolynomial(x, x, e, c);
  return c[0] / rest_det_[e];
}

int InversionFilter::FirstInverted(const double* x) const {
  for (size_t e = 0; e < elements_.size(); ++e) {
    if (!(VolumeRatio(x, static_cast<int>(e)) > 0.0)) return static_cast<int>(e);
  }
  return -1;
}

void InversionFilter::OnAccepted(const double* x) {
  std::copy(x, x + accepted_.size(), accepted_.begin());
}

bool InversionFilter::IsStepValid(const double* x) const {
  return IsFeasible(x) && MaxStepSize(accepted_.data(), x) >= 1.0;
}

double InversionFilter::MaxStepSize(const double* from, const double* to) const {
  double t = 1.0;
  for (size_t e = 0; e < elements_.size(); ++e) {
    double c[4];
    PathPolynomial(from, to, static_cast<int>(e), c);
    if (!(c[0] > 0.0)) return 0.0;  // already degenerate at the start
    // Scale by the start value: c[0] = 1 (the roots do not change).
    for (int k = dimension_; k >= 0; --k) c[k] /= c[0];
    // Quick exit: |c1| + |c2| + |c3| < 1 means no root in [0, 1].
    if (std::abs(c[1]) + std::abs(c[2]) + std::abs(c[3]) < 1.0) continue;
    t = std::min(t, FirstNonPositive(c, dimension_));
  }
  return t;
}

bool InversionFilter::IsFeasible(const double* x) const { return FirstInverted(x) < 0; }

std::vector<double> InversionFilter::Diagnostics(const double* x) const {
  double min_j = std::numeric_limits<double>::infinity();
  for (size_t e = 0; e < elements_.size(); ++e) {
    min_j = std::min(min_j, VolumeRatio(x, static_cast<int>(e)));
  }
  return {min_j};
}

}  // namespace ipstep

#include "geometry/exact_orientation.h"

#include <cmath>
#include <vector>

namespace ipstep {

namespace {

using Expansion = std::vector<double>;

constexpr double kEps = 1.1102230246251565e-16;  // 2^-53

void TwoSum(double a, double b, double* x, double* y) {
  *x = a + b;
  const double bv = *x - a;
  const double av = *x - bv;
  *y = (a - av) + (b - bv);
}

// e + b (e nonoverlapping, increasing magnitude), zero components dropped
// (the rest keeps both properties).
void Grow(Expansion* e, double b) {
  double q = b;
  size_t kept = 0;
  for (size_t k = 0; k < e->size(); ++k) {
    double sum, error;
    TwoSum(q, (*e)[k], &sum, &error);
    if (error != 0.0) (*e)[kept++] = error;
    q = sum;
  }
  e->resize(kept);
  if (q != 0.0) e->push_back(q);
}

Expansion Difference(double a, double b) {
  Expansion e;
  Grow(&e, a);
  Grow(&e, -b);
  return e;
}

Expansion Sum(Expansion e, const Expansion& f) {
  for (double component : f) Grow(&e, component);
  return e;
}

Expansion Negate(Expansion e) {
  for (double& component : e) component = -component;
  return e;
}

Expansion Product(const Expansion& e, const Expansion& f) {
  Expansion h;
  for (double x : e) {
    for (double y : f) {
      const double p = x * y;
      Grow(&h, std::fma(x, y, -p));
      Grow(&h, p);
    }
  }
  return h;
}

int Sign(const Expansion& e) {
  for (auto it = e.rbegin(); it != e.rend(); ++it) {
    if (*it > 0.0) return 1;
    if (*it < 0.0) return -1;
  }
  return 0;
}

int SignOf(double v) { return v > 0.0 ? 1 : (v < 0.0 ? -1 : 0); }

}  // namespace

int ExactOrient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  const Eigen::Vector3d& d) {
  const double ax = a[0] - d[0], ay = a[1] - d[1], az = a[2] - d[2];
  const double bx = b[0] - d[0], by = b[1] - d[1], bz = b[2] - d[2];
  const double cx = c[0] - d[0], cy = c[1] - d[1], cz = c[2] - d[2];
  const double bycz = by * cz, bzcy = bz * cy, bzcx = bz * cx, bxcz = bx * cz;
  const double bxcy = bx * cy, bycx = by * cx;
  const double det = ax * (bycz - bzcy) + ay * (bzcx - bxcz) + az * (bxcy - bycx);
  const double permanent = std::abs(ax) * (std::abs(bycz) + std::abs(bzcy)) +
                           std::abs(ay) * (std::abs(bzcx) + std::abs(bxcz)) +
                           std::abs(az) * (std::abs(bxcy) + std::abs(bycx));
  // Every product exactly zero (no underflow: see the header): det = 0.
  if (permanent == 0.0) return 0;
  const double bound = (7.0 + 56.0 * kEps) * kEps * permanent;
  if (det > bound || -det > bound) return SignOf(det);
  // Exact.
  const Expansion ex = Difference(a[0], d[0]), ey = Difference(a[1], d[1]),
                  ez = Difference(a[2], d[2]);
  const Expansion fx = Difference(b[0], d[0]), fy = Difference(b[1], d[1]),
                  fz = Difference(b[2], d[2]);
  const Expansion gx = Difference(c[0], d[0]), gy = Difference(c[1], d[1]),
                  gz = Difference(c[2], d[2]);
  const Expansion m0 = Sum(Product(fy, gz), Negate(Product(fz, gy)));
  const Expansion m1 = Sum(Product(fz, gx), Negate(Product(fx, gz)));
  const Expansion m2 = Sum(Product(fx, gy), Negate(Product(fy, gx)));
  return Sign(Sum(Sum(Product(ex, m0), Product(ey, m1)), Product(ez, m2)));
}

int ExactOrient2d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  int i, int j) {
  const double left = (b[i] - a[i]) * (c[j] - a[j]);
  const double right = (b[j] - a[j]) * (c[i] - a[i]);
  const double det = left - right;
  if (left == 0.0 && right == 0.0) return 0;
  const double bound = (3.0 + 16.0 * kEps) * kEps * (std::abs(left) + std::abs(right));
  if (det > bound || -det > bound) return SignOf(det);
  const Expansion l = Product(Difference(b[i], a[i]), Difference(c[j], a[j]));
  const Expansion r = Product(Difference(b[j], a[j]), Difference(c[i], a[i]));
  return Sign(Sum(l, Negate(r)));
}

}  // namespace ipstep

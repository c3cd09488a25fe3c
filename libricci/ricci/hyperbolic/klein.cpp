#include "ricci/hyperbolic/klein.h"

#include <cmath>

namespace ricci {

Eigen::Vector3d hyperboloid_from_poincare(Complex z) {
  const double r2 = std::norm(z);
  const double s = 1.0 / ((1.0 - std::abs(z)) * (1.0 + std::abs(z)));
  return {(1.0 + r2) * s, 2.0 * z.real() * s, 2.0 * z.imag() * s};
}

Complex klein_from_poincare(Complex z) { return 2.0 * z / (1.0 + std::norm(z)); }

Complex poincare_from_klein(Complex k) {
  const double a = std::abs(k);
  return k / (1.0 + std::sqrt((1.0 - a) * (1.0 + a)));
}

Eigen::Matrix3d lorentz_matrix(const Mobius& map) {
  // X -> M X M^* is linear in x; its columns are the images of the basis vectors.
  Eigen::Matrix3d l;
  for (int c = 0; c < 3; ++c) {
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    x[c] = 1.0;
    Eigen::Matrix2cd X;
    X << x[0], Complex(x[1], x[2]), Complex(x[1], -x[2]), x[0];
    X *= 0.5;
    const Eigen::Matrix2cd Y = map.m * X * map.m.adjoint();
    l(0, c) = (Y(0, 0).real() + Y(1, 1).real());
    l(1, c) = 2.0 * Y(0, 1).real();
    l(2, c) = 2.0 * Y(0, 1).imag();
  }
  return l;
}

Complex apply_projective(const Eigen::Matrix3d& transition, Complex k) {
  const Eigen::Vector3d y = transition * Eigen::Vector3d(1.0, k.real(), k.imag());
  return {y[1] / y[0], y[2] / y[0]};
}

}  // namespace ricci

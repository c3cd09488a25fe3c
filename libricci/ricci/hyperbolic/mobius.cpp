#include "ricci/hyperbolic/mobius.h"

#include <cmath>

namespace ricci {

Mobius Mobius::from_matrix(const Eigen::Matrix2cd& matrix) {
  return {matrix / std::sqrt(matrix.determinant())};
}

Mobius Mobius::from_rotation_point(double theta, Complex z0) {
  const Complex half = std::polar(1.0, 0.5 * theta);
  const double s = std::sqrt((1.0 - std::abs(z0)) * (1.0 + std::abs(z0)));
  Eigen::Matrix2cd m;
  m << half / s, -half * z0 / s, -std::conj(half * z0) / s, std::conj(half) / s;
  return {m};
}

Mobius Mobius::euclidean(double theta, Complex t) {
  const Complex half = std::polar(1.0, 0.5 * theta);
  Eigen::Matrix2cd m;
  m << half, t / half, 0.0, 1.0 / half;
  return {m};
}

Mobius Mobius::inverse() const {
  Eigen::Matrix2cd r;
  r << m(1, 1), -m(0, 1), -m(1, 0), m(0, 0);
  return {r};
}

double Mobius::theta() const { return std::remainder(2.0 * std::arg(m(0, 0)), 2.0 * M_PI); }

double mobius_distance(const Mobius& a, const Mobius& b) {
  return std::min((a.m - b.m).norm(), (a.m + b.m).norm());
}

double distance_to_identity(const Mobius& a) { return mobius_distance(a, Mobius::identity()); }

Mobius mobius_mean(const Mobius* maps, int count) {
  Eigen::Matrix2cd sum = maps[0].m;
  for (int k = 1; k < count; ++k) {
    const bool flip = (maps[k].m - maps[0].m).norm() > (maps[k].m + maps[0].m).norm();
    sum += flip ? Eigen::Matrix2cd(-maps[k].m) : maps[k].m;
  }
  return Mobius::from_matrix(sum);
}

Mobius disk_to_centre(Complex p, Complex q) {
  // T(z) = (z - p) / (1 - conj(p) z) takes p to 0; then turn T(q) onto the positive axis.
  const Complex tq = (q - p) / (1.0 - std::conj(p) * q);
  return Mobius::from_rotation_point(-std::arg(tq), p);
}

Mobius plane_to_centre(Complex p, Complex q) {
  const double phi = -std::arg(q - p);
  return Mobius::euclidean(phi, -std::polar(1.0, phi) * p);
}

double disk_distance(Complex z, Complex w) {
  return 2.0 * std::atanh(std::abs(z - w) / std::abs(1.0 - std::conj(z) * w));
}

MobiusL MobiusL::from_matrix(const Eigen::Matrix<ComplexL, 2, 2>& matrix) {
  return MobiusL(matrix / std::sqrt(matrix.determinant()));
}

MobiusL MobiusL::from_rotation_point(long double theta, ComplexL z0) {
  const ComplexL half = std::polar(1.0L, 0.5L * theta);
  const long double s = std::sqrt((1.0L - std::abs(z0)) * (1.0L + std::abs(z0)));
  Eigen::Matrix<ComplexL, 2, 2> m;
  m << half / s, -half * z0 / s, -std::conj(half * z0) / s, std::conj(half) / s;
  return MobiusL(m);
}

MobiusL MobiusL::inverse() const {
  Eigen::Matrix<ComplexL, 2, 2> r;
  r << m(1, 1), -m(0, 1), -m(1, 0), m(0, 0);
  return MobiusL(r);
}

MobiusL disk_to_centre(ComplexL p, ComplexL q) {
  const ComplexL tq = (q - p) / (1.0L - std::conj(p) * q);
  return MobiusL::from_rotation_point(-std::arg(tq), p);
}

MobiusL plane_to_centre(ComplexL p, ComplexL q) {
  const long double phi = -std::arg(q - p);
  const ComplexL half = std::polar(1.0L, 0.5L * phi);
  Eigen::Matrix<ComplexL, 2, 2> m;
  m << half, -std::polar(1.0L, phi) * p / half, 0.0L, 1.0L / half;
  return MobiusL(m);
}

MobiusL mobius_mean(const MobiusL* maps, int count) {
  Eigen::Matrix<ComplexL, 2, 2> sum = maps[0].m;
  for (int k = 1; k < count; ++k) {
    const bool flip = (maps[k].m - maps[0].m).norm() > (maps[k].m + maps[0].m).norm();
    if (flip) {
      sum -= maps[k].m;
    } else {
      sum += maps[k].m;
    }
  }
  return MobiusL::from_matrix(sum);
}

double distance_to_identity(const MobiusL& a) {
  const Eigen::Matrix<ComplexL, 2, 2> id = Eigen::Matrix<ComplexL, 2, 2>::Identity();
  return static_cast<double>(std::min((a.m - id).norm(), (a.m + id).norm()));
}

}  // namespace ricci

#pragma once
// Möbius maps z -> (a z + b) / (c z + d) as 2x2 complex matrices of determinant 1 (defined up to
// sign). Orientation-preserving isometries of the Poincaré disk are the SU(1,1) ones,
// [[a, b], [conj b, conj a]] with |a|² - |b|² = 1, equivalently z -> e^{iθ} (z - z0) / (1 -
// conj(z0) z) (hyperbolic-and-real-projective-structure §4.3, eq. 14). Euclidean motions are
// [[e^{iθ/2}, t e^{-iθ/2}], [0, e^{-iθ/2}]], so one type carries the side pairings of the H2 and E2
// domains alike.
#include <complex>

#include <Eigen/Core>
#include <Eigen/LU>

namespace ricci {

using Complex = std::complex<double>;

/// A Möbius map as a 2x2 complex matrix of determinant 1.
struct Mobius {
  Eigen::Matrix2cd m = Eigen::Matrix2cd::Identity();

  [[nodiscard]] static Mobius identity() { return {}; }
  /// The matrix scaled to determinant 1. \pre det(matrix) != 0.
  [[nodiscard]] static Mobius from_matrix(const Eigen::Matrix2cd& matrix);
  /// z -> e^{iθ} (z - z0) / (1 - conj(z0) z), an isometry of the disk. \pre |z0| < 1.
  [[nodiscard]] static Mobius from_rotation_point(double theta, Complex z0);
  /// z -> e^{iθ} z + t, a Euclidean motion of the plane.
  [[nodiscard]] static Mobius euclidean(double theta, Complex t);

  [[nodiscard]] Complex operator()(Complex z) const {
    return (m(0, 0) * z + m(0, 1)) / (m(1, 0) * z + m(1, 1));
  }
  /// Composition: (A * B)(z) = A(B(z)).
  [[nodiscard]] Mobius operator*(const Mobius& other) const { return {m * other.m}; }
  [[nodiscard]] Mobius inverse() const;

  /// For a disk isometry: the point sent to 0 (z0 = -b/a) and the rotation θ = 2 arg a in
  /// (-π, π], so that the map is z -> e^{iθ} (z - z0) / (1 - conj(z0) z).
  [[nodiscard]] Complex z0() const { return -m(0, 1) / m(0, 0); }
  [[nodiscard]] double theta() const;
};

/// min over the sign of ||A - (±B)||_F: zero when A and B are the same map (both of
/// determinant 1, so the figure is scale-free).
[[nodiscard]] double mobius_distance(const Mobius& a, const Mobius& b);
/// mobius_distance(a, identity).
[[nodiscard]] double distance_to_identity(const Mobius& a);

/// Mean of maps that agree up to rounding: the sign of each is aligned with the first, the
/// matrices averaged and rescaled to determinant 1. \pre not empty.
[[nodiscard]] Mobius mobius_mean(const Mobius* maps, int count);

/// The disk isometry taking p to 0 and q onto the positive real axis. \pre |p|, |q| < 1, p != q.
[[nodiscard]] Mobius disk_to_centre(Complex p, Complex q);
/// The Euclidean motion taking p to 0 and q onto the positive real axis. \pre p != q.
[[nodiscard]] Mobius plane_to_centre(Complex p, Complex q);

/// Extended precision for the disk layout's frames and the side pairings (x86-64 long double:
/// 64-bit mantissa, 2^11 times finer than double). The relator is a word of ~50 pairings whose
/// partial products reach norm 1e3..1e6 on genus 3-4 domains, so an error in a pairing shows in
/// the relation residual multiplied by the square of that norm; the pairings come from layout
/// coordinates near the rim, where double keeps 1e-14 in hyperbolic distance. (The larger part
/// was the metric's angle defects, see polish_h2.h; the products themselves are multiplied in
/// __float128, see fuchsian.cpp.) Outputs stay double.
using ComplexL = std::complex<long double>;

/// A Möbius map in extended precision (same conventions as Mobius).
struct MobiusL {
  Eigen::Matrix<ComplexL, 2, 2> m = Eigen::Matrix<ComplexL, 2, 2>::Identity();

  MobiusL() = default;
  explicit MobiusL(const Eigen::Matrix<ComplexL, 2, 2>& matrix) : m(matrix) {}
  explicit MobiusL(const Mobius& a) : m(a.m.cast<ComplexL>()) {}
  /// The matrix scaled to determinant 1. \pre det(matrix) != 0.
  [[nodiscard]] static MobiusL from_matrix(const Eigen::Matrix<ComplexL, 2, 2>& matrix);
  /// z -> e^{iθ} (z - z0) / (1 - conj(z0) z). \pre |z0| < 1.
  [[nodiscard]] static MobiusL from_rotation_point(long double theta, ComplexL z0);
  [[nodiscard]] ComplexL operator()(ComplexL z) const {
    return (m(0, 0) * z + m(0, 1)) / (m(1, 0) * z + m(1, 1));
  }
  [[nodiscard]] MobiusL operator*(const MobiusL& other) const { return MobiusL(m * other.m); }
  [[nodiscard]] MobiusL inverse() const;
  /// Rounded to double.
  [[nodiscard]] Mobius to_double() const { return {m.cast<Complex>()}; }
};

/// disk_to_centre in extended precision.
[[nodiscard]] MobiusL disk_to_centre(ComplexL p, ComplexL q);
/// plane_to_centre in extended precision.
[[nodiscard]] MobiusL plane_to_centre(ComplexL p, ComplexL q);
/// mobius_mean in extended precision. \pre not empty.
[[nodiscard]] MobiusL mobius_mean(const MobiusL* maps, int count);
/// distance_to_identity in extended precision (rounded to double at the end).
[[nodiscard]] double distance_to_identity(const MobiusL& a);

/// Hyperbolic distance in the Poincaré disk, 2 atanh(|z - w| / |1 - conj(z) w|).
[[nodiscard]] double disk_distance(Complex z, Complex w);

/// Euclidean radius in the disk of a point at hyperbolic distance `d` from 0: tanh(d/2).
[[nodiscard]] inline double disk_radius(double d) { return std::tanh(0.5 * d); }

}  // namespace ricci

#pragma once
// Quadruple precision (__float128, 113-bit mantissa; long double where the compiler has none) for
// the disk layout's frames, its positions and the side pairings at genus >= 6. A point at
// hyperbolic distance d from the frame's centre lies 2 e^-d from the rim, so a coordinate with
// relative rounding eps is exact only to ~eps e^d in hyperbolic distance: long double (eps 5e-20)
// keeps 1e-12 at d = 17 (genus 4) but 1e-5 at d = 34, the far end of a genus-10 domain, and every
// pairing computed from such coordinates is off by as much. The transcendental functions below
// come from GCC's libquadmath when the build found it (MSP_HAVE_QUADMATH), else they are the
// long double ones (then only + - * / and the square root carry quad digits).
#include "ricci/hyperbolic/mobius.h"

namespace ricci {

#ifdef __SIZEOF_FLOAT128__
__extension__ typedef __float128 RealQ;
#else
typedef long double RealQ;
#endif

/// sqrt(x) for x >= 0: the long double root refined by one Newton step.
[[nodiscard]] RealQ sqrt_q(RealQ x);
/// exp, sinh, asinh, tanh, atan2, sin and cos in quad precision (see the top of the file).
[[nodiscard]] RealQ exp_q(RealQ x);
[[nodiscard]] RealQ sinh_q(RealQ x);
[[nodiscard]] RealQ asinh_q(RealQ x);
[[nodiscard]] RealQ tanh_q(RealQ x);
[[nodiscard]] RealQ atan2_q(RealQ y, RealQ x);
[[nodiscard]] RealQ sin_q(RealQ x);
[[nodiscard]] RealQ cos_q(RealQ x);
/// True when the functions above carry quad digits (libquadmath was linked).
[[nodiscard]] bool has_quad_transcendentals();
/// pi in quad precision.
[[nodiscard]] RealQ pi_q();

struct ComplexQ {
  RealQ re = 0, im = 0;

  ComplexQ() = default;
  ComplexQ(RealQ real, RealQ imag) : re(real), im(imag) {}
  explicit ComplexQ(ComplexL z) : re(z.real()), im(z.imag()) {}
  [[nodiscard]] ComplexL to_long() const {
    return {static_cast<long double>(re), static_cast<long double>(im)};
  }
  [[nodiscard]] RealQ norm() const { return re * re + im * im; }  ///< |z|^2
  [[nodiscard]] ComplexQ conj() const { return {re, -im}; }
  ComplexQ operator+(const ComplexQ& b) const { return {re + b.re, im + b.im}; }
  ComplexQ operator-(const ComplexQ& b) const { return {re - b.re, im - b.im}; }
  ComplexQ operator*(const ComplexQ& b) const {
    return {re * b.re - im * b.im, re * b.im + im * b.re};
  }
  ComplexQ operator/(const ComplexQ& b) const {
    const RealQ n = b.norm();
    return {(re * b.re + im * b.im) / n, (im * b.re - re * b.im) / n};
  }
};

/// A Möbius map with a quad-precision matrix [[a, b], [c, d]] (not normalised unless said).
struct MobiusQ {
  ComplexQ a{1, 0}, b{0, 0}, c{0, 0}, d{1, 0};

  MobiusQ() = default;
  MobiusQ(ComplexQ a_, ComplexQ b_, ComplexQ c_, ComplexQ d_) : a(a_), b(b_), c(c_), d(d_) {}
  explicit MobiusQ(const MobiusL& m) : a(m.m(0, 0)), b(m.m(0, 1)), c(m.m(1, 0)), d(m.m(1, 1)) {}
  [[nodiscard]] ComplexQ operator()(ComplexQ z) const { return (a * z + b) / (c * z + d); }
  [[nodiscard]] MobiusQ operator*(const MobiusQ& o) const {
    return {a * o.a + b * o.c, a * o.b + b * o.d, c * o.a + d * o.c, c * o.b + d * o.d};
  }
  /// The adjugate: the inverse map, with the same determinant.
  [[nodiscard]] MobiusQ inverse() const { return {d, ComplexQ{} - b, ComplexQ{} - c, a}; }
  /// The matrix scaled to determinant 1. \pre a non-zero determinant.
  [[nodiscard]] MobiusQ normalised() const;
  /// Rounded to long double (normalised first).
  [[nodiscard]] MobiusL to_long() const;
};

/// disk_to_centre(p, q) in quad precision (determinant 1). \pre |p|, |q| < 1, p != q.
[[nodiscard]] MobiusQ disk_to_centre_q(ComplexQ p, ComplexQ q);

/// mobius_mean in quad precision (determinant 1). \pre count >= 1.
[[nodiscard]] MobiusQ mobius_mean_q(const MobiusQ* maps, int count);

}  // namespace ricci

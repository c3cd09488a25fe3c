#include "ricci/hyperbolic/mobius_q.h"

#include <cmath>

#if defined(MSP_HAVE_QUADMATH) && defined(__SIZEOF_FLOAT128__)
#include <quadmath.h>
#define MSP_QUAD(f) f##q
#else
#define MSP_QUAD(f) f##_l
#endif

namespace ricci {
namespace {

// sqrt(z): the long double root refined by one Newton step. \pre z != 0.
ComplexQ complex_sqrt_q(ComplexQ z) {
  const ComplexL s0 = std::sqrt(z.to_long());
  const ComplexQ s(s0);
  return ComplexQ(RealQ(0.5), RealQ(0)) * (s + z / s);
}

ComplexQ scaled(ComplexQ z, RealQ x) { return {z.re * x, z.im * x}; }

}  // namespace

RealQ sqrt_q(RealQ x) {
  if (!(x > 0)) return 0;
  const RealQ s = std::sqrt(static_cast<long double>(x));
  return RealQ(0.5) * (s + x / s);
}

#if !(defined(MSP_HAVE_QUADMATH) && defined(__SIZEOF_FLOAT128__))
// Without libquadmath the long double functions take the rounded argument.
namespace {
long double to_l(RealQ x) { return static_cast<long double>(x); }
RealQ exp_l(RealQ x) { return std::exp(to_l(x)); }
RealQ sinh_l(RealQ x) { return std::sinh(to_l(x)); }
RealQ asinh_l(RealQ x) { return std::asinh(to_l(x)); }
RealQ tanh_l(RealQ x) { return std::tanh(to_l(x)); }
RealQ atan2_l(RealQ y, RealQ x) { return std::atan2(to_l(y), to_l(x)); }
RealQ sin_l(RealQ x) { return std::sin(to_l(x)); }
RealQ cos_l(RealQ x) { return std::cos(to_l(x)); }
}  // namespace
#endif

RealQ exp_q(RealQ x) { return MSP_QUAD(exp)(x); }
RealQ sinh_q(RealQ x) { return MSP_QUAD(sinh)(x); }
RealQ asinh_q(RealQ x) { return MSP_QUAD(asinh)(x); }
RealQ tanh_q(RealQ x) { return MSP_QUAD(tanh)(x); }
RealQ atan2_q(RealQ y, RealQ x) { return MSP_QUAD(atan2)(y, x); }
RealQ sin_q(RealQ x) { return MSP_QUAD(sin)(x); }
RealQ cos_q(RealQ x) { return MSP_QUAD(cos)(x); }

RealQ pi_q() {
#if defined(MSP_HAVE_QUADMATH) && defined(__SIZEOF_FLOAT128__)
  static const RealQ pi = 4 * atanq(RealQ(1));
  return pi;
#else
  return 3.141592653589793238462643383279502884L;
#endif
}

bool has_quad_transcendentals() {
#if defined(MSP_HAVE_QUADMATH) && defined(__SIZEOF_FLOAT128__)
  return true;
#else
  return false;
#endif
}

MobiusQ MobiusQ::normalised() const {
  const ComplexQ root = complex_sqrt_q(a * d - b * c);
  return {a / root, b / root, c / root, d / root};
}

MobiusL MobiusQ::to_long() const {
  const MobiusQ n = normalised();
  Eigen::Matrix<ComplexL, 2, 2> m;
  m << n.a.to_long(), n.b.to_long(), n.c.to_long(), n.d.to_long();
  return MobiusL(m);
}

MobiusQ disk_to_centre_q(ComplexQ p, ComplexQ q) {
  // T(z) = (z - p) / (1 - conj(p) z) takes p to 0; then u = conj(T(q)) / |T(q)| turns T(q) onto
  // the positive axis: z -> u T(z), the matrix [[u, -u p], [-conj(p), 1]] of determinant
  // u (1 - |p|^2), scaled by sqrt(u) and sqrt(1 - |p|^2).
  const ComplexQ one(1, 0);
  const ComplexQ tq = (q - p) / (one - p.conj() * q);
  const ComplexQ u = scaled(tq.conj(), 1 / sqrt_q(tq.norm()));
  const ComplexQ root_u = complex_sqrt_q(u);
  const RealQ s = 1 / sqrt_q((1 - p.re) * (1 + p.re) - p.im * p.im);
  const ComplexQ k = scaled(one / root_u, s);
  return {u * k, ComplexQ{} - u * p * k, ComplexQ{} - p.conj() * k, k};
}

MobiusQ mobius_mean_q(const MobiusQ* maps, int count) {
  const MobiusQ first = maps[0].normalised();
  MobiusQ sum = first;
  for (int k = 1; k < count; ++k) {
    const MobiusQ m = maps[k].normalised();
    // The sign of the normalised matrix is free: take the one nearer the first.
    const RealQ minus = (m.a - first.a).norm() + (m.b - first.b).norm() + (m.c - first.c).norm() +
                        (m.d - first.d).norm();
    const RealQ plus = (m.a + first.a).norm() + (m.b + first.b).norm() + (m.c + first.c).norm() +
                       (m.d + first.d).norm();
    const RealQ sign = plus < minus ? -1 : 1;
    sum.a = sum.a + scaled(m.a, sign);
    sum.b = sum.b + scaled(m.b, sign);
    sum.c = sum.c + scaled(m.c, sign);
    sum.d = sum.d + scaled(m.d, sign);
  }
  return sum.normalised();
}

}  // namespace ricci

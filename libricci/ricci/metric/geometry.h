#pragma once
// Background geometries (E2, H2, S2) of a discrete metric: per-triangle formulas shared by the
// curvature, the circle-packing metrics and the Ricci flow. Everything here is inline and
// allocation-free because the flow evaluates it millions of times.
//
// Notation (Ricci-flow paper §IV): a triangle has vertices 0,1,2, l[k] is the length of the edge
// opposite vertex k and theta[k] the corner angle at vertex k. The "geometry sine" f is
// f(x) = x (E2), sinh x (H2), sin x (S2).
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace ricci {

/// Constant-curvature background geometry of a discrete metric.
enum class Geometry { euclidean, hyperbolic, spherical };

/// "euclidean", "hyperbolic", "spherical".
std::string to_string(Geometry geometry);

/// Sign of the background curvature: 0 (E2), -1 (H2), +1 (S2); the λ of Gauss-Bonnet
/// Σ K_i + λ Σ A_f = 2πχ.
inline int curvature_sign(Geometry g) {
  return g == Geometry::euclidean ? 0 : (g == Geometry::hyperbolic ? -1 : 1);
}

/// f(x) = x, sinh x or sin x.
inline double geometry_sine(Geometry g, double x) {
  switch (g) {
    case Geometry::euclidean:
      return x;
    case Geometry::hyperbolic:
      return std::sinh(x);
    default: return std::sin(x);
  }
}

/// c(x) = 1, cosh x or cos x: the derivative of geometry_sine.
inline double geometry_cosine(Geometry g, double x) {
  switch (g) {
    case Geometry::euclidean:
      return 1.0;
    case Geometry::hyperbolic:
      return std::cosh(x);
    default: return std::cos(x);
  }
}

/// Corner angles of a triangle with side lengths l (l[k] opposite vertex k) by the half-angle
/// formula tan(θ_k/2) = sqrt(f(s-l_a) f(s-l_b) / (f(s) f(s-l_k))), s the half perimeter, which
/// stays accurate near 0 and π where acos does not. Also gives cos θ_k and sin θ_k from the same
/// products (no further trigonometry) when `cosine`/`sine` are not null. Returns false (and
/// leaves the outputs unset) when the lengths violate the triangle inequality, or in S2 when the
/// perimeter reaches 2π.
inline bool triangle_angles(Geometry g, const double l[3], double theta[3],
                            double* cosine = nullptr, double* sine = nullptr) {
  // s - l_k = (l_a + l_b - l_k)/2 with the subtraction done first against the longer of l_a,
  // l_b: exact by Sterbenz's lemma when they are close, so needles keep their small angles.
  double d[3];
  for (int k = 0; k < 3; ++k) {
    const double a = l[(k + 1) % 3], b = l[(k + 2) % 3];
    d[k] = 0.5 * ((std::max(a, b) - l[k]) + std::min(a, b));
  }
  const double s = 0.5 * (l[0] + l[1] + l[2]);
  if (!(d[0] > 0 && d[1] > 0 && d[2] > 0)) return false;
  if (g == Geometry::spherical && !(s < M_PI)) return false;
  const double f[3] = {geometry_sine(g, d[0]), geometry_sine(g, d[1]), geometry_sine(g, d[2])};
  const double fs = geometry_sine(g, s);
  // In E2 the largest angle is closed from the other two below, so its arc tangent is not
  // needed when it is known beforehand: opposite a side longer than the others by a relative
  // 1e-6, its angle exceeds theirs by far more than their rounding (tan²(θ/2) grows by
  // (d_j / d_k)² > (1 + 2e-6)²), and the closing would pick it. Near ties keep all three.
  const int longest = l[0] >= l[1] ? (l[0] >= l[2] ? 0 : 2) : (l[1] >= l[2] ? 1 : 2);
  const bool known = g == Geometry::euclidean &&
                     l[longest] > (1.0 + 1e-6) * l[(longest + 1) % 3] &&
                     l[longest] > (1.0 + 1e-6) * l[(longest + 2) % 3];
  for (int k = 0; k < 3; ++k) {
    // tan(θ_k/2) = y/x with x² = f(s) f(s-l_k), y² = f(s-l_a) f(s-l_b).
    const double x2 = fs * f[k], y2 = f[(k + 1) % 3] * f[(k + 2) % 3];
    if (!(known && k == longest)) theta[k] = 2.0 * std::atan2(std::sqrt(y2), std::sqrt(x2));
    if (cosine) cosine[k] = (x2 - y2) / (x2 + y2);
    if (sine) sine[k] = 2.0 * std::sqrt(x2 * y2) / (x2 + y2);
  }
  if (g == Geometry::euclidean) {
    // Rounding would make each face's angle sum miss π by a biased ulp; summed over a million
    // faces that drift breaks Σ K = 2πχ at the 1e-10 level. Closing the sum on the largest
    // angle (whose relative accuracy matters least) leaves an unbiased ulp per face.
    const int big = known ? longest
                          : theta[0] >= theta[1] ? (theta[0] >= theta[2] ? 0 : 2)
                                                 : (theta[1] >= theta[2] ? 1 : 2);
    theta[big] = M_PI - (theta[(big + 1) % 3] + theta[(big + 2) % 3]);
  }
  return true;
}

/// Area of a triangle from its lengths and angles: Heron's formula in E2 (stable ordering),
/// π - Σθ in H2 (defect), Σθ - π in S2 (excess).
inline double triangle_area(Geometry g, const double l[3], const double theta[3]) {
  if (g == Geometry::euclidean) {
    // Kahan's ordering a >= b >= c keeps Heron accurate for needle triangles.
    double a = l[0], b = l[1], c = l[2];
    if (a < b) std::swap(a, b);
    if (b < c) std::swap(b, c);
    if (a < b) std::swap(a, b);
    const double p = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
    return 0.25 * std::sqrt(std::max(p, 0.0));
  }
  const double sum = theta[0] + theta[1] + theta[2];
  return g == Geometry::hyperbolic ? M_PI - sum : sum - M_PI;
}

/// Partial derivatives of the corner angles with respect to the side lengths:
/// dtheta_dl[k][e] = ∂θ_k/∂l_e, given cos θ and sin θ of the three corners. From the cosine law
/// of each geometry: ∂θ_k/∂l_k = f(l_k) / (f(l_a) f(l_b) sin θ_k) and
/// ∂θ_k/∂l_a = -∂θ_k/∂l_k cos θ_b (a, b the other two vertices). Non-degenerate triangles only.
inline void triangle_angle_length_jacobian(Geometry g, const double l[3], const double cosine[3],
                                           const double sine[3], double dtheta_dl[3][3]) {
  const double f[3] = {geometry_sine(g, l[0]), geometry_sine(g, l[1]), geometry_sine(g, l[2])};
  for (int k = 0; k < 3; ++k) {
    const int a = (k + 1) % 3, b = (k + 2) % 3;
    const double diag = f[k] / (f[a] * f[b] * sine[k]);
    dtheta_dl[k][k] = diag;
    dtheta_dl[k][a] = -diag * cosine[b];
    dtheta_dl[k][b] = -diag * cosine[a];
  }
}

}  // namespace ricci

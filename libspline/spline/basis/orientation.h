#pragma once
// Robust orientation predicates and the half-open triangle rule of the simplex-spline base case.
//
// Sums of DMS basis functions over a triangulation are exact identities of polynomial pieces; they
// stay exact on knot lines only if every point on a shared edge is given to exactly one of the two
// triangles. We decide that by symbolic perturbation: u is treated as u + eps*d + eps^2*d_perp
// (d_perp = d rotated by +90 degrees, eps -> 0+), with exact signs, so the choice is consistent
// across all triangles of all knot sets at once, also at vertices.
#include <Eigen/Core>

namespace spline {

/// Sign (+1, 0, -1) of det[b - a, c - a]: +1 when a, b, c turn counter-clockwise. Exact (Shewchuk's
/// floating-point filter with an exact expansion fallback), for finite inputs without overflow.
[[nodiscard]] int orient2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                           const Eigen::Vector2d& c);

/// det[b - a, c - a] (twice the signed area) to within a few ulps of the exact value, also for
/// slivers where the plain formula cancels: used once per knot triple when a DAG is built.
/// Compensated arithmetic (the correctly rounded value or its neighbour) unless the products
/// cancel to below ~6e-14 of their size; then an exact expansion.
[[nodiscard]] double accurate_det2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                    const Eigen::Vector2d& c);

/// Exact sign of cross(q - p, d) = (q - p).x * d.y - (q - p).y * d.x.
[[nodiscard]] int cross_sign(const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                             const Eigen::Vector2d& d);

/// Direction of the symbolic perturbation that decides which side of a line a point on it belongs
/// to. Rigid motions of a chart should rotate it with the chart, so that a point on an edge picks
/// the same side in every chart. Must be non-zero.
struct TieBreak {
  Eigen::Vector2d direction{1.0, 0.0};  ///< d: the point is pushed by eps*d first
};

/// True when u (perturbed by the tie-break) lies on the left of the directed line p -> q.
/// Antisymmetric: exactly one of left_of(p, q, u) and left_of(q, p, u) holds when p != q.
[[nodiscard]] bool left_of(const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                           const Eigen::Vector2d& u, const TieBreak& tie);

/// Half-open membership of u in the counter-clockwise triangle (a, b, c) (pre: orient2d(a,b,c) > 0).
/// The triangles of any triangulation partition the plane exactly under this rule.
[[nodiscard]] bool in_half_open_triangle(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                         const Eigen::Vector2d& c, const Eigen::Vector2d& u,
                                         const TieBreak& tie);

}  // namespace spline

#pragma once
// Knot clouds of DMS triangular B-splines: each domain vertex v carries knots t_{v,0} = v and
// t_{v,1..n} close to v (manifold-splines paper section 5).
//
// The rule (make_knot_cloud): the n extra knots sit on a jittered spiral-like pattern around v,
// at distance r * s_j (s_j in [1 - radius_jitter, 1]) with r = radius_fraction * (smallest inradius
// of the triangles incident to v), at angles (j - 1) * 2 pi / (n + 1/2) + jitter, the whole pattern
// rotated to stay as far as possible (modulo pi) from the directions of v's edges.
//  - moving the corners of a triangle with inradius rho by at most r < rho / 2 keeps its incentre
//    strictly inside (the signed distance to each moved edge line stays above
//    (L rho - L r - 2 r (rho + r)) / (L + 2 r) > 0, L the edge length, rho <= L / (2 sqrt 3)), so
//    every shifted triangle [t_{0,b0}, t_{1,b1}, t_{2,b2}] keeps I's orientation and their
//    intersection Omega_I contains a disc: the DMS knot-net conditions (check_dms_conditions).
//  - angular spacing s = 2 pi / (n + 1/2): the multiple of s nearest to pi misses it by at least
//    s / 4, so with angular jitter below s / 8 per knot no two knots of a cloud lie on a line
//    through v (they stay (1/4 - 2 angle_jitter) s away from it); the rotation away from edge
//    directions keeps t_{v,j} off the line through v and a neighbour (such near-collinear
//    triples make sub-simplex-splines nearly singular: large derivatives).
//  - the seeded jitter breaks the coincidences of regular meshes (translated copies of one pattern
//    put knots of different clouds on common lines). The seed is mixed with the vertex id, so the
//    cloud does not depend on evaluation order, and the pattern is measured from the direction of
//    the first ring neighbour, so a rigid motion of the one-ring moves the cloud with it.
// Default radius: 0.4 of the smallest incident inradius (about 0.12 of the edge length for an
// equilateral triangle). Partition of unity is exact for any radius satisfying the conditions, but
// derivatives grow like 1/r and r -> 0 degenerates to C0 Bezier patches; 0.4 keeps the margin of
// the condition while making the knot lines well separated.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "spline/planar/triangulation.h"

namespace spline {

/// Knots of one domain vertex in one planar frame: knots[0] = vertex position, knots[1..n].
struct KnotCloud {
  std::vector<Eigen::Vector2d> knots;

  [[nodiscard]] int degree() const { return static_cast<int>(knots.size()) - 1; }
};

/// Options of the knot-cloud rule.
struct KnotCloudOptions {
  /// r / (smallest inradius of incident triangles), in (0, 0.5): the range where the knot-net
  /// conditions are guaranteed (see above).
  double radius_fraction = 0.4;
  double radius_jitter = 0.4;    ///< knot distances vary in [(1 - jitter) r, r], in [0, 1)
  double angle_jitter = 0.06;    ///< angular jitter, fraction of the pattern spacing, in [0, 0.1]
  std::uint64_t seed = 1;        ///< mixed with the vertex id
};

/// Cloud of one vertex from its one-ring laid out in the plane.
/// \param ring neighbours' positions counter-clockwise around center (an open fan for a boundary
///        vertex, then triangles are (center, ring[i], ring[i+1]) only).
/// \throw ricci::InvalidInputError on degree outside 1..kMaxDmsDegree, bad options, a ring with
///        fewer than 2 neighbours or a degenerate incident triangle.
[[nodiscard]] KnotCloud make_knot_cloud(int degree, std::uint64_t vertex_id,
                                        const Eigen::Vector2d& center,
                                        const std::vector<Eigen::Vector2d>& ring, bool ring_closed,
                                        const KnotCloudOptions& options = {});

/// Clouds of every vertex of a planar triangulation (vertices in no triangle get all knots at the
/// vertex; they carry no basis function).
/// \throw ricci::InvalidInputError / ricci::TopologyError as validate() and vertex_rings().
[[nodiscard]] std::vector<KnotCloud> make_knot_clouds(const PlanarTriangulation& triangulation,
                                                      int degree,
                                                      const KnotCloudOptions& options = {});

/// The cloud moved by the rigid motion x -> rotation * x + translation (chart transfer).
[[nodiscard]] KnotCloud transformed(const KnotCloud& cloud, const Eigen::Matrix2d& rotation,
                                    const Eigen::Vector2d& translation);

}  // namespace spline

#pragma once
// The DMS knot-net conditions (Dahmen-Micchelli-Seidel 1992; Fong-Seidel 1993) under which the
// triangular B-splines form a partition of unity and reproduce polynomials of degree <= n:
//   (1) for every triangle I = (v0, v1, v2) and every beta with |beta| <= n, the shifted triangle
//       [t_{0,beta0}, t_{1,beta1}, t_{2,beta2}] is non-degenerate and oriented like I;
//   (2) the intersection Omega_I of these triangles has a non-empty interior;
//   (3) triangles sharing an edge use the same knots for the shared vertices. With one cloud per
//       vertex (our representation) this holds by construction, and together with (1) for both
//       triangles it puts their third clouds on opposite sides of every line t_{0,i} t_{1,j},
//       which makes the edge terms of the two B-patches cancel.
// Additionally, smoothness C^{n-1} needs the knots of each knot set V_beta^I in general position
// (no three collinear); we report the smallest normalised triple area as a margin.
#include <vector>

#include "spline/knots/knot_cloud.h"
#include "spline/planar/triangulation.h"

namespace spline {

/// What check_dms_conditions measured.
struct DmsConditionReport {
  bool satisfied = true;  ///< conditions (1) and (2) hold for every triangle
  /// min over I, |beta| <= n of d(shifted triangle) / d(I): positive iff (1) holds.
  double min_orientation_ratio = 1.0;
  /// min over I of area(Omega_I) / area(I): positive iff (2) holds.
  double min_knot_region_ratio = 1.0;
  /// min over I, |beta| = n and knot triples of V_beta^I of |det| / diameter(V_beta^I)^2
  /// (0 when some knot set has three collinear knots).
  double min_general_position = 1.0;
  std::vector<int> failing_triangles;  ///< triangles violating (1) or (2)
};

/// Checks the knot-net conditions of every triangle.
/// \throw ricci::InvalidInputError on a cloud count other than the vertex count or unequal
///        degrees (and as validate()).
[[nodiscard]] DmsConditionReport check_dms_conditions(const PlanarTriangulation& triangulation,
                                                      const std::vector<KnotCloud>& clouds);

}  // namespace spline

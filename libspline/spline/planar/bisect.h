#pragma once
// Local refinement of a planar triangulation by longest-edge bisection (Rivara): a triangle is
// split at the midpoint of its longest edge, together with the neighbour across that edge, after
// the neighbour has been split the same way until that edge is its longest too. The result stays
// conforming (no hanging vertices, which a DMS space cannot have) and its angles stay bounded
// below by about half of the initial smallest angle, whatever the number of levels.
#include <Eigen/Core>
#include <functional>

#include "spline/planar/triangulation.h"

namespace spline {

/// Splits triangles until every triangle's longest edge is at most size(its centroid), or the
/// triangulation has max_triangles triangles. Triangles stay counter-clockwise; existing vertices
/// keep their indices (new ones are appended).
/// \throw ricci::InvalidInputError when the triangulation is invalid (validate) or size returns
///        a non-positive or non-finite value.
void refine_to_size(PlanarTriangulation& triangulation,
                    const std::function<double(const Eigen::Vector2d&)>& size,
                    int max_triangles = 200000);

}  // namespace spline

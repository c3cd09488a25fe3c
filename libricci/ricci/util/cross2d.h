#pragma once
// The 2D cross product, the one helper for it (orientation tests, signed areas in charts).
#include <Eigen/Core>

namespace ricci {

/// a.x b.y - a.y b.x: the z component of the cross product of two plane vectors, twice the
/// signed area of the triangle (0, a, b), positive when b lies counter-clockwise from a.
/// Plain floating point; spline/basis/orientation.h has the exact predicates.
[[nodiscard]] inline double cross2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace ricci

#pragma once
// Ear clipping of one (possibly non-planar, non-convex) polygon in its best-fit plane.
#include <array>
#include <functional>
#include <vector>

#include <Eigen/Core>

namespace ricci {

/// Splits a simple polygon into corners.size() - 2 triangles of corner indices (0-based, into
/// `corners`), keeping the polygon's winding. The polygon is projected onto the plane of its
/// Newell normal and ears are clipped there, so concave polygons stay inside their outline,
/// unlike a blind fan. `diagonal_allowed(i, j)` may veto a diagonal between corners i and j
/// (e.g. one that already is a mesh edge); vetoed ears are used only when no other ear exists.
/// Degenerate input (collinear or self-intersecting) still yields triangles; it never throws.
[[nodiscard]] std::vector<std::array<int, 3>> triangulate_polygon(
    const std::vector<Eigen::Vector3d>& corners,
    const std::function<bool(int, int)>& diagonal_allowed = {});

}  // namespace ricci

#pragma once
// A triangulation laid out in the plane: a chart of the affine atlas, or a planar domain.
#include <Eigen/Core>
#include <vector>

namespace spline {

/// Vertex positions and counter-clockwise triangles (indices into positions).
struct PlanarTriangulation {
  std::vector<Eigen::Vector2d> positions;
  std::vector<Eigen::Vector3i> triangles;
};

/// Checks that positions are finite, indices in range and distinct, and every triangle is
/// strictly counter-clockwise.
/// \throw ricci::InvalidInputError naming the first offending vertex or triangle.
void validate(const PlanarTriangulation& triangulation);

/// For each vertex, its one-ring: the neighbours in counter-clockwise order, and whether the ring
/// is closed (interior vertex) or an open fan (boundary vertex; the fan then starts at the
/// boundary edge whose other triangle is missing).
struct VertexRing {
  std::vector<int> neighbours;
  bool closed = false;
};

/// One-rings of all vertices (pre: validate() passes; each vertex fan is a single manifold fan).
/// \throw ricci::TopologyError when a vertex's triangles do not form a single fan.
[[nodiscard]] std::vector<VertexRing> vertex_rings(const PlanarTriangulation& triangulation);

/// Radius of the inscribed circle of triangle (a, b, c).
[[nodiscard]] double inradius(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                              const Eigen::Vector2d& c);

}  // namespace spline

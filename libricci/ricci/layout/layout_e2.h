#pragma once
// Isometric placement of a flat, simply connected mesh in the plane from its edge lengths
// (manifold-splines paper, section 4, step 5; ALGORITHMS.md section 5).
#include <functional>

#include <Eigen/Core>

#include "ricci/mesh/mesh.h"

namespace ricci {

struct LayoutE2Options {
  /// Face placed first (vertex 0 at the origin, its first edge along +x); -1 = the face
  /// farthest (in face hops) from the boundary, which keeps the growth front short.
  int seed_face = -1;
};

struct LayoutE2Result {
  Eigen::MatrixX2d positions;  ///< #V by 2, by vertex index of the laid-out mesh.
  int seed_face = -1;
  /// Smallest signed face area (positive = counter-clockwise, as in the mesh's orientation).
  double min_signed_area = 0.0;
  int flipped_faces = 0;  ///< Faces with signed area <= 0.
  /// max over edges of | |x_i - x_j| - l_ij | / l_ij: closure error of the growth.
  double max_relative_length_error = 0.0;
  /// Largest sum of corner angles at one vertex (radians). Above 2*pi the layout wraps around
  /// that vertex and the chart overlaps itself there (e.g. a cone copy with a too wide sector).
  double max_vertex_angle = 0.0;
};

/// Places the faces one by one, each new vertex at the intersection of two circles on the left
/// of the known edge (counter-clockwise faces). Faces are grown breadth-first across edges.
/// \pre mesh is connected and simply connected (a disk, e.g. a SlicedMesh); lengths by edge
///      index satisfy the triangle inequality in every face.
/// \throw InvalidInputError on bad lengths (naming the face), TopologyError if some face cannot
///        be reached from the seed across edges.
[[nodiscard]] LayoutE2Result layout_e2(const Mesh& mesh, const Eigen::VectorXd& edge_lengths,
                                       const LayoutE2Options& options = {});

/// Places c so that |c - a| = l_ac, |c - b| = l_bc and (a, b, c) is counter-clockwise: the
/// intersection of two circles, with the height taken from Kahan's stable Heron formula so that
/// needle triangles keep all their digits. A triangle inequality violation is clamped (c lands
/// on the line through a and b).
[[nodiscard]] Eigen::Vector2d place_third_vertex(const Eigen::Vector2d& a,
                                                 const Eigen::Vector2d& b, double l_ac,
                                                 double l_bc);

/// Area of a triangle with side lengths a, b, c (Kahan's ordering of Heron's formula); 0 when
/// the triangle inequality fails.
[[nodiscard]] double triangle_area_from_lengths(double a, double b, double c);

/// Angle opposite the side `opposite` in a triangle with sides (opposite, b, c), by the stable
/// half-angle formula. Clamped to [0, pi] when the triangle inequality fails.
[[nodiscard]] double corner_angle_from_lengths(double opposite, double b, double c);

/// Signed area, max relative length error, flipped faces and max vertex angle of `positions`
/// against `edge_lengths` (fills those fields of `result`).
void measure_layout(const Mesh& mesh, const Eigen::VectorXd& edge_lengths,
                    const Eigen::MatrixX2d& positions, LayoutE2Result& result);

}  // namespace ricci

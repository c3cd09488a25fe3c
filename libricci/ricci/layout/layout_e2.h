#pragma once
// Isometric placement of a flat, simply connected mesh in the plane from its edge lengths
// (manifold-splines paper, section 4, step 5).
#include <functional>

#include <Eigen/Core>

#include "ricci/mesh/mesh.h"

namespace ricci {

struct LayoutE2Options {
  /// Face placed first (vertex 0 at the origin, its first edge along +x); -1 = the face
  /// farthest (in face hops) from the boundary, which keeps the growth front short, or, when the
  /// face sizes span more than 2^8 (a large cone), the smallest face.
  int seed_face = -1;
};

struct LayoutE2Result {
  Eigen::MatrixX2d positions;  ///< #V by 2, by vertex index of the laid-out mesh.
  /// Low parts of the double-double positions the growth computed: the developed position of
  /// vertex v is positions(v) + positions_low(v) to ~1e-32 of the chart's size. Near a large
  /// cone the flat metric's edges shrink like r^(angle/2pi - 1) (1e-17 of the chart at a 10pi
  /// cone of a 100k-face mesh), far below the rounding of `positions` at the cone's copies away
  /// from the origin; edge_vector keeps those edges to full relative precision.
  Eigen::MatrixX2d positions_low;
  /// The vector from vertex `from` to vertex `to`, from the double-double positions (relative
  /// accuracy ~1e-16 of its own length however small, when positions_low is filled).
  [[nodiscard]] Eigen::Vector2d edge_vector(int from, int to) const;
  /// By halfedge (of a face): its direction in the chart (radians, (-pi, pi]) as the growth
  /// developed it, a sum of corner angles in long double. Unlike edge_vector it does not depend
  /// on the edge's length: next to a 38 pi cone edges reach 1e-31 of the chart, where even the
  /// double-double positions no longer give a direction.
  Eigen::VectorXd halfedge_directions;
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

/// Edge lengths in long double, by edge index: the metric the polish (metric/polish_e2.h) made,
/// before its rounding to double.
using LongLengths = Eigen::Matrix<long double, Eigen::Dynamic, 1>;

/// `lengths` + `low` (low parts; empty for none) in long double.
/// \throw InvalidInputError if `low` is neither empty nor of the size of `lengths`.
[[nodiscard]] LongLengths long_lengths(const Eigen::VectorXd& lengths, const Eigen::VectorXd& low);

/// Directions (angles, radians) of a->w and b->w in the counter-clockwise triangle (a, b, w) with
/// sides l_ab, l_aw, l_bw, given the direction of a->b: each adds a corner angle (half-angle
/// formula in long double) to a direction carried from the last face. A development by
/// directions never takes an edge's direction from its endpoints' positions, which across the
/// short edge of a needle (l/d up to 6e4 in the intrinsic triangulations at 1.6M faces) would
/// multiply their rounding by l/d at every needle of a chain.
struct DevelopedDirections {
  long double a_to_w = 0, b_to_w = 0;
};
[[nodiscard]] DevelopedDirections develop_directions(long double a_to_b, long double l_ab,
                                                     long double l_aw, long double l_bw);

/// Places the faces one by one, each new vertex at its metric distance from a placed corner
/// along the direction develop_directions carries across the faces (counter-clockwise faces),
/// in double-double coordinates. Faces are grown
/// breadth-first, except that faces below half the median size come first, smallest scale
/// first (breadth-first among faces within a factor 16 in size):
/// a vertex is placed through a chain of faces, and where two chains meet the metric's
/// rounding-level curvature error shows up multiplied by the size of the loop they enclose.
/// Growing the tiny faces at a large cone outwards from the cone keeps those loops as small as
/// the faces, so every edge keeps ~1e-12 relative accuracy instead of ~1e-16 of the chart.
/// \pre mesh is connected and simply connected (a disk, e.g. a SlicedMesh); lengths by edge
///      index satisfy the triangle inequality in every face.
/// \throw InvalidInputError on bad lengths (naming the face), TopologyError if some face cannot
///        be reached from the seed across edges.
[[nodiscard]] LayoutE2Result layout_e2(const Mesh& mesh, const Eigen::VectorXd& edge_lengths,
                                       const LayoutE2Options& options = {});

/// As above with long-double lengths edge_lengths + lengths_low (the polish's metric: at 1.6M
/// faces its rounding to double alone leaves curvature defects of 2e-11 at needles, which the
/// layout would multiply by the chart's size). The accuracy fields measure against the doubles.
/// \throw InvalidInputError also if lengths_low is neither empty nor of the lengths' size.
[[nodiscard]] LayoutE2Result layout_e2(const Mesh& mesh, const Eigen::VectorXd& edge_lengths,
                                       const Eigen::VectorXd& lengths_low,
                                       const LayoutE2Options& options = {});

/// Places c so that |c - a| = l_ac, |c - b| = l_bc and (a, b, c) is counter-clockwise: the
/// intersection of two circles, with the height taken from Kahan's stable Heron formula so that
/// needle triangles keep all their digits. A triangle inequality violation is clamped (c lands
/// on the line through a and b).
[[nodiscard]] Eigen::Vector2d place_third_vertex(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                                 double l_ac, double l_bc);

/// Area of a triangle with side lengths a, b, c (Kahan's ordering of Heron's formula); 0 when
/// the triangle inequality fails.
[[nodiscard]] double triangle_area_from_lengths(double a, double b, double c);

/// Angle opposite the side `opposite` in a triangle with sides (opposite, b, c), by the stable
/// half-angle formula. Clamped to [0, pi] when the triangle inequality fails.
[[nodiscard]] double corner_angle_from_lengths(double opposite, double b, double c);

/// Signed area, max relative length error, flipped faces and max vertex angle of the result's
/// positions (double-double when positions_low is filled) against `edge_lengths` (fills those
/// fields of `result`).
void measure_layout(const Mesh& mesh, const Eigen::VectorXd& edge_lengths, LayoutE2Result& result);

/// The face farthest, in hops across edges, from the mesh's boundary (face 0 for a closed
/// mesh): seeding a layout there halves the depth of the growth compared with a boundary seed,
/// and closure error grows with depth. Shared by the E2 and H2 layouts.
[[nodiscard]] int central_face_of(const Mesh& mesh);

}  // namespace ricci

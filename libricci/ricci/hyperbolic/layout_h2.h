#pragma once
// Isometric placement of a hyperbolic, simply connected mesh in the Poincaré disk from its edge
// lengths (hyperbolic-and-real-projective-structure §4.2, which intersects Euclidean images of
// hyperbolic circles), by the Möbius-to-centre method instead: every face is constructed at the
// centre (one edge from 0 along the positive real axis, the third vertex in polar coordinates,
// radius tanh(l/2) at the corner angle), where the disk loses no digits, and moved out by its
// frame, a Möbius map; a neighbour's frame is this frame times the map between the two centred
// constructions, so rounding is not amplified from face to face.
#include <vector>

#include <Eigen/Core>

#include "ricci/hyperbolic/mobius.h"
#include "ricci/hyperbolic/mobius_q.h"
#include "ricci/hyperbolic/polish_h2.h"
#include "ricci/mesh/mesh.h"

namespace ricci {

struct LayoutH2Options {
  /// Face placed first (its first corner's from-vertex at 0, its first edge along the positive
  /// real axis); -1 = the face farthest in face hops from the boundary (shortest growth front).
  int seed_face = -1;
  /// With seed_face = -1: lay out once, find the approximate hyperbolic minimax centre of the
  /// vertices (Badoiu-Clarkson steps towards the farthest vertex) and lay out again from a face
  /// at it. The domain then reaches less far towards the ideal boundary, where disk coordinates
  /// lose digits (1 - |z| shrinks like e^{-d}), which is what the 1e-9 accuracy needs.
  bool recentre = true;
};

struct LayoutH2Result {
  Eigen::VectorXcd positions;  ///< By vertex index of the laid-out mesh; |z| < 1.
  /// The same in extended precision (frames are composed in long double): the side pairings
  /// are computed from these, since rounding a coordinate near the rim to double moves it by
  /// ~1e-14 in hyperbolic distance, which the generators' long words amplify.
  std::vector<ComplexL> precise_positions;
  /// The same in quad precision (frames are composed in it, mobius_q.h): the side pairings of
  /// domains reaching far towards the rim (genus >= 6) are computed from these.
  std::vector<ComplexQ> quad_positions;
  int seed_face = -1;
  /// Smallest signed (Euclidean) area of a face's vertex triangle: positive = counter-clockwise,
  /// which for the disk's geodesic triangles is the hyperbolic orientation too.
  double min_signed_area = 0.0;
  int flipped_faces = 0;
  /// max over edges of |d_H(z_i, z_j) - l_ij| / l_ij.
  double max_relative_length_error = 0.0;
  double max_radius = 0.0;  ///< max |z|: how close the layout comes to the ideal boundary.
};

/// Lays out the faces breadth-first from the seed.
/// \pre mesh is connected and simply connected (e.g. a SlicedMesh); lengths (hyperbolic, by
///      edge index) satisfy the triangle inequality in every face.
/// \throw InvalidInputError on bad lengths or seed (naming the face); TopologyError when a face
///        cannot be reached from the seed.
[[nodiscard]] LayoutH2Result layout_h2(const Mesh& mesh, const Eigen::VectorXd& edge_lengths,
                                       const LayoutH2Options& options = {});

/// The same from extended-precision lengths, which the frames use as they are.
[[nodiscard]] LayoutH2Result layout_h2(const Mesh& mesh, const LengthsL& edge_lengths,
                                       const LayoutH2Options& options = {});

/// The same from quad-precision lengths (e.g. polish_h2_lengths' quad_lengths): the faces'
/// corners and the frames are computed in quad precision throughout.
[[nodiscard]] LayoutH2Result layout_h2(const Mesh& mesh, const LengthsQ& edge_lengths,
                                       const LayoutH2Options& options = {});

/// Orientation, closure and radius of `positions` against `edge_lengths` (fills those fields).
void measure_layout_h2(const Mesh& mesh, const Eigen::VectorXd& edge_lengths,
                       const Eigen::VectorXcd& positions, LayoutH2Result& result);

/// Approximate centre (minimising the largest hyperbolic distance) of the points.
[[nodiscard]] Complex hyperbolic_centre(const Eigen::VectorXcd& points, int iterations = 60);

}  // namespace ricci

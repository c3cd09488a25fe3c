#pragma once
// Delaunay edge flips restricted to edges whose two faces are (nearly) coplanar: the
// triangulation of a flat region changes, the surface does not (or by at most the tolerance).
// Marching-cubes meshes are full of caps (an angle near pi) and slivers lying in one plane with a
// neighbour; flipping them away is what keeps the inversive-distance metric, which reproduces the
// mesh's shape, away from the triangle inequality under a large cone (CEPS gets its conformality
// by intrinsic Delaunay flips during the flow; these are the extrinsic ones that cost nothing).
#include "ricci/mesh/mesh.h"

namespace ricci {

struct FlatFlipOptions {
  /// Largest angle (radians) between the normals of an edge's two faces for it to be flipped.
  /// The flipped diagonal leaves the surface by at most about this angle times a quarter of the
  /// shorter diagonal, so 1e-3 keeps every point within 0.03% of the local edge length.
  double max_normal_angle = 1e-3;
  /// Also flipped, whatever the normals: edges whose quad is this thin, i.e. whose two diagonals
  /// pass within this fraction of the median edge length of each other (the most the surface
  /// moves). Caps (an angle near pi) have their apex next to their long edge and go this way.
  /// 0 = off.
  double max_relative_deviation = 0.0;
  /// Edges with a quad vertex within `protected_rings` rings of `protected_vertex` stay (-1 =
  /// none): the valences there are what a cone's existence condition counts.
  int protected_vertex = -1;
  int protected_rings = 0;
  /// An edge is not Delaunay when the angles opposite it sum to more than pi plus this (radians).
  double delaunay_margin = 1e-9;
  /// Flips allowed, as a multiple of the edge count (a safety cap: in the plane Lawson's flips
  /// end after O(|E|^2) at worst and near |E| in practice).
  double max_flips_per_edge = 4.0;
};

struct FlatFlipResult {
  int flips = 0;
  /// Largest normal angle (radians) across an edge that was flipped.
  double max_normal_angle_flipped = 0.0;
  /// Edges that are not Delaunay at the end (too bent to flip, or the flip would make a double
  /// edge or a valence-2 vertex).
  int non_delaunay_left = 0;
};

/// Flips every interior edge that is not Delaunay (3D corner angles) and whose faces are
/// coplanar within options.max_normal_angle, until none is left. Vertex indices and positions
/// are kept; edge and face indices change.
/// \pre a triangle 2-manifold without degenerate faces.
[[nodiscard]] FlatFlipResult flip_flat_edges_to_delaunay(Mesh& mesh, const FlatFlipOptions& options = {});

}  // namespace ricci

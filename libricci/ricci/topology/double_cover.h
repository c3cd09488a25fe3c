#pragma once
// Double covering of an open surface (discrete-surface-ricci-flow §V; hyperbolic-and-real-
// projective-structure §4.1): two copies, the second with its orientation reversed, glued along
// their common boundary. The result is closed, of genus 2g + b - 1, and carries an orientation-
// reversing symmetry whose fixed set is the old boundary, so the uniformization metric of the
// double makes every boundary loop a geodesic.
#include <vector>

#include "ricci/mesh/mesh.h"

namespace ricci {

struct DoubleCover {
  Mesh mesh;
  /// The open surface that was doubled: the input, with every interior edge that joined two
  /// boundary vertices split at its midpoint (its two copies would otherwise be parallel edges).
  /// Indices below refer to this mesh; its first vertices and faces keep the input's indices
  /// except for the faces a split replaced.
  Mesh original;
  int split_edges = 0;
  /// By vertex index of the double: the vertex of the original it copies.
  std::vector<int> to_original_vertex;
  /// By face index of the double: faces [0, F) are the faces of `original` (same index and
  /// orientation), faces [F, 2F) their mirror copies, with reversed orientation.
  int original_faces = 0;
  /// By original vertex index: its vertex in the mirror copy (the same vertex on the boundary).
  std::vector<int> mirror_vertex;
};

/// \pre a connected oriented 2-manifold with at least one boundary loop.
/// \throw TopologyError for a closed mesh or when a mirror face cannot be glued (non-manifold).
[[nodiscard]] DoubleCover double_cover(const Mesh& mesh);

}  // namespace ricci

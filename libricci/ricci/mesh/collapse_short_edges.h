#pragma once
// Collapse of edges far shorter than the mesh's typical edge: marching cubes leaves vertices a
// millionth of an edge apart (genus2_100k has 24 edges under 1e-4 of its median), and each makes a
// needle whose long sides must stay equal to within that length under any metric change, which
// pins a Ricci flow (the inversive-distance flow stalls there, a hundred rings from the cone).
// Merging the two vertices moves the surface by at most the edge's length.
#include <vector>

#include "ricci/mesh/mesh.h"

namespace ricci {

struct ShortEdgeOptions {
  /// Edges shorter than this times the median edge length are collapsed.
  double relative_length = 0.01;
  /// An input vertex that must survive (the other end of its short edges is merged into it);
  /// -1 for none.
  int keep_vertex = -1;
};

struct ShortEdgeCollapse {
  Mesh mesh;  ///< The mesh after the collapses (vertices re-indexed, positions unchanged).
  /// input_vertex[v] = index in the input of vertex v of `mesh`.
  std::vector<int> input_vertex;
  int collapses = 0;
  /// Short edges left because collapsing them would break the 2-manifold (OpenMesh's
  /// is_collapse_ok) or remove keep_vertex.
  int short_edges_left = 0;
};

/// Collapses every edge shorter than options.relative_length times the median edge length into
/// one of its ends (the surviving vertex keeps its position), repeatedly, while the result stays
/// a 2-manifold.
/// \pre a triangle 2-manifold.
[[nodiscard]] ShortEdgeCollapse collapse_short_edges(const Mesh& mesh, const ShortEdgeOptions& options = {});

}  // namespace ricci

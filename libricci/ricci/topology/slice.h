#pragma once
// Slicing a mesh open along a set of cut edges: every vertex is split into one copy per wedge of
// faces between consecutive cut (or boundary) edges around it.
#include <array>
#include <vector>

#include <Eigen/Core>

#include "ricci/mesh/mesh.h"

namespace ricci {

/// The two sides of one cut edge in the sliced mesh.
struct CutEdgeSides {
  EdgeHandle edge;  ///< In the original mesh.
  /// side[k] is the sliced-mesh halfedge that lies in the face of the original halfedge
  /// (edge, k), running the same way (both are halfedges with a face).
  HalfedgeHandle side[2];
};

struct SlicedMesh {
  /// The sliced mesh. Face f here is face f of the original (same index); vertex positions are
  /// the original ones. Map halfedges (hence corners) with from_original_halfedge.
  Mesh mesh;
  std::vector<int> to_original_vertex;  ///< By sliced vertex index.
  std::vector<int> to_original_edge;    ///< By sliced edge index.
  /// By sliced halfedge index: the original halfedge in the same face; for sliced boundary
  /// halfedges, the original opposite of their inner halfedge's original (an original boundary
  /// halfedge, or the far side of a cut).
  std::vector<int> to_original_halfedge;
  /// By original halfedge index (halfedges with a face): the sliced vertex that is to_vertex(h)
  /// inside face(h), i.e. the copy of that corner. -1 for face-less halfedges.
  std::vector<int> corner_vertex;
  /// By original halfedge index (with a face): the sliced halfedge of the same face; else -1.
  std::vector<int> from_original_halfedge;
  std::vector<CutEdgeSides> cut_sides;  ///< One per cut edge, in edge-index order.
  int boundary_loop_count = 0;
  int euler_characteristic = 0;
  int component_count = 0;
};

/// Splits `mesh` along the edges flagged in `is_cut_edge` (by edge index; boundary edges may
/// not be flagged). Does not require the result to be a disk: see check_disk.
/// \throw InvalidInputError on a size mismatch or a flagged boundary edge; TopologyError if
///        OpenMesh cannot hold the sliced faces (non-manifold input).
[[nodiscard]] SlicedMesh slice_along(const Mesh& mesh, const std::vector<char>& is_cut_edge);

/// \throw TopologyError unless the sliced mesh is one component with one boundary loop and
///        Euler characteristic 1 (a topological disk). `what` prefixes the message.
void check_disk(const SlicedMesh& sliced, const char* what = "slice");

/// Edge lengths by original edge index carried to the sliced mesh's edges.
[[nodiscard]] Eigen::VectorXd sliced_edge_lengths(const SlicedMesh& sliced,
                                                  const Eigen::VectorXd& original_lengths);

/// The original halfedges of face f in corner order: h0 = halfedge_handle(f), h1 = next(h0),
/// h2 = next(h1). Corner k of face f is to_vertex(h_k).
[[nodiscard]] std::array<HalfedgeHandle, 3> face_halfedges(const Mesh& mesh, FaceHandle f);

}  // namespace ricci

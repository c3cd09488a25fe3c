#pragma once
// Cut graph through a root vertex by tree-cotree (Eppstein; Erickson-Whittlesey's greedy system
// of loops): slicing the surface along it yields a topological disk (manifold-splines paper,
// section 4, step 4).
//
// Open surfaces are handled by contracting every boundary loop to a single node: on that closed
// quotient surface the tree-cotree leftover edges give the 2g loops, and the tree itself supplies
// the cuts that join the root to every boundary loop.
#include <vector>

#include <Eigen/Core>

#include "ricci/mesh/boundary_loops.h"  // find_boundary_loops, used with the cut graph
#include "ricci/mesh/mesh.h"

namespace ricci {

enum class CutPathKind {
  homology_loop,       ///< One of the 2g loops through the root.
  boundary_connector,  ///< Tree path from the root to a boundary loop (open surfaces).
};

/// A path of the cut graph, as halfedges walked in order. Paths are continuous except where they
/// pass through a boundary loop: there the next halfedge may start at another vertex of the same
/// boundary loop (the boundary itself is already a cut).
struct CutPath {
  CutPathKind kind = CutPathKind::homology_loop;
  std::vector<HalfedgeHandle> halfedges;
  /// homology_loop: the cotree-leftover edge that closes the loop, walked as `generator`
  /// (so the loop is tree path root->from(generator), generator, tree path to(generator)->root).
  HalfedgeHandle generator;
  int boundary_loop = -1;  ///< boundary_connector: index of the boundary loop reached.
  double length = 0.0;     ///< Sum of edge lengths (the greedy weight for loops).
};

struct CutGraphOptions {
  /// Compute loops but skip the check that each loop's halfedges chain up (debug aid only).
  bool check_paths = true;
};

struct CutGraph {
  VertexHandle root;
  int euler_characteristic = 0;
  int boundary_loop_count = 0;
  int genus = 0;
  /// 2g loops from root to root, in tree-cotree order (a homology basis, not necessarily
  /// canonical: see fundamental_polygon_word).
  std::vector<CutPath> loops;
  /// One path per boundary loop that does not contain the root.
  std::vector<CutPath> boundary_connectors;
  /// By edge index: 1 if the edge is cut (never an original boundary edge).
  std::vector<char> is_cut_edge;
  /// By vertex index: index of the boundary loop through the vertex, or -1.
  std::vector<int> boundary_loop_of_vertex;
  /// Boundary loops as halfedge cycles (the halfedges without face, walked by next()).
  std::vector<std::vector<HalfedgeHandle>> boundary_loops;
};

/// Tree-cotree cut graph rooted at `root`. The tree is the shortest-path tree under
/// `edge_lengths` (by edge index; empty = the mesh's 3D lengths); the cotree is the maximum
/// spanning tree of the dual graph weighted by the length of the loop each edge closes.
/// \pre mesh is a connected, oriented 2-manifold triangle mesh (closed or with boundary).
/// \throw InvalidInputError on bad lengths or root; TopologyError if the mesh is disconnected or
///        the leftover count differs from 2g.
[[nodiscard]] CutGraph compute_cut_graph(const Mesh& mesh, VertexHandle root,
                                         const Eigen::VectorXd& edge_lengths = {},
                                         const CutGraphOptions& options = {});

/// An approximate centre of the surface under `edge_lengths` (empty = 3D lengths): the vertex
/// minimising the largest graph distance to `samples` farthest-point samples (the first the
/// vertex farthest from vertex 0). A root there keeps the greedy loops short, and so the side
/// pairings' words and the matrices a relator multiplies (hyperbolic/fuchsian.h).
/// \pre connected mesh; samples >= 1.
/// \throw InvalidInputError on bad lengths or an empty mesh.
[[nodiscard]] VertexHandle central_vertex(const Mesh& mesh,
                                          const Eigen::VectorXd& edge_lengths = {},
                                          int samples = 8);

/// `count` vertices spread over the surface by farthest-point sampling under `edge_lengths`
/// (empty = 3D lengths): `first`, then each time the vertex farthest from those chosen (fewer
/// when the mesh has fewer vertices).
/// \pre connected mesh.
/// \throw InvalidInputError on bad lengths or a vertex out of range.
[[nodiscard]] std::vector<VertexHandle> spread_vertices(const Mesh& mesh, VertexHandle first,
                                                        const Eigen::VectorXd& edge_lengths = {},
                                                        int count = 8);

/// Checks lengths (size, finite, positive) or returns the mesh's 3D lengths when empty.
/// \throw InvalidInputError naming the first bad edge.
[[nodiscard]] Eigen::VectorXd checked_edge_lengths(const Mesh& mesh,
                                                   const Eigen::VectorXd& edge_lengths);

}  // namespace ricci

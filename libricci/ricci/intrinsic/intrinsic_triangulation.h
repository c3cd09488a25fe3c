#pragma once
// An intrinsic triangulation of a closed surface: the input's vertices, a connectivity that
// changes by edge flips, and per-edge logarithmic lengths. It is a Delta-complex (two edges may
// join the same two vertices, an edge may be a loop), as intrinsic Delaunay triangulations
// need. The lengths are those of a discrete conformal class: at vertex scale factors u the
// edge ij has length exp(log_length_ij + (u_i + u_j) / 2), and a flip replaces the diagonal by
// the Ptolemy relation l_kl l_ij = l_ik l_jl + l_il l_jk, which commutes with vertex scaling
// (Gillespie, Springborn, Crane 2021, "Discrete conformal equivalence of polyhedral surfaces",
// section 3; Springborn 2020, "Ideal hyperbolic polyhedra and discrete uniformization").
#include <vector>

#include <Eigen/Core>

#include "ricci/mesh/mesh.h"
#include "ricci/metric/mesh_tables.h"

namespace ricci {

/// Halfedges are numbered face by face: halfedge h lies in face h / 3 and the face's halfedges
/// 3f, 3f+1, 3f+2 run counter-clockwise, each from its tail to the next one's tail.
struct IntrinsicTriangulation {
  int vertex_count = 0;
  std::vector<int> tail;           ///< By halfedge: the vertex it leaves.
  std::vector<int> twin;           ///< By halfedge: the opposite halfedge.
  std::vector<int> edge;           ///< By halfedge: its edge.
  std::vector<int> edge_halfedge;  ///< By edge: one of its two halfedges.
  /// By edge: log of the length at u = 0 (half the Penner coordinate lambda).
  Eigen::VectorXd log_length;

  [[nodiscard]] int face_count() const { return static_cast<int>(tail.size()) / 3; }
  [[nodiscard]] int edge_count() const { return static_cast<int>(edge_halfedge.size()); }
  [[nodiscard]] static int next(int h) { return h - h % 3 + (h + 1) % 3; }
  [[nodiscard]] static int prev(int h) { return h - h % 3 + (h + 2) % 3; }
  /// The vertex the halfedge enters.
  [[nodiscard]] int head(int h) const { return tail[static_cast<size_t>(next(h))]; }
  /// Log length of edge e at scale factors u (by vertex).
  [[nodiscard]] double log_length_at(int e, const Eigen::VectorXd& u) const;
};

/// The mesh's connectivity with the lengths `edge_lengths` (by OpenMesh edge index); vertex
/// indices are kept.
/// \pre a closed triangle 2-manifold; lengths positive, each face a Euclidean triangle.
/// \throw InvalidInputError for a mesh with boundary, a size mismatch or a non-positive length.
[[nodiscard]] IntrinsicTriangulation make_intrinsic_triangulation(
    const Mesh& mesh, const Eigen::VectorXd& edge_lengths);

/// Whether edge e can be flipped: its two halfedges lie in different faces.
[[nodiscard]] bool is_flippable(const IntrinsicTriangulation& tri, int e);

/// Flips edge e in place (Ptolemy length). The edge keeps its index; the halfedges of the two
/// faces are renumbered. \pre is_flippable(tri, e).
void flip_edge(IntrinsicTriangulation& tri, int e);

/// 2 (cos alpha + cos beta), alpha and beta the angles opposite edge e at scale factors u,
/// computed as (b^2 + c^2 - a^2) / (b c) per face, which is defined even where a triangle
/// inequality fails. The edge is Delaunay when this is >= 0 (alpha + beta <= pi).
[[nodiscard]] double delaunay_measure(const IntrinsicTriangulation& tri, int e,
                                      const Eigen::VectorXd& u);

struct DelaunayFlipResult {
  int flips = 0;
  bool delaunay = false;  ///< false when the flip budget ran out first
};

/// Flips non-Delaunay edges (delaunay_measure < -margin) until none is left, at scale factors u
/// (Lawson's algorithm; it ends for decorated surfaces, Springborn 2020, section 5). At most
/// max_flips_per_edge * #E flips. When `flip_log` is given, each flipped edge is appended to it
/// in order (replayed by point_tracking.h's IntrinsicCorrespondence).
inline constexpr double kMaxFlipsPerEdge = 200.0;  ///< flip_to_delaunay's default budget
DelaunayFlipResult flip_to_delaunay(IntrinsicTriangulation& tri, const Eigen::VectorXd& u,
                                    double margin = 1e-12,
                                    double max_flips_per_edge = kMaxFlipsPerEdge,
                                    std::vector<int>* flip_log = nullptr);

/// Corner angles (row f: the angles at the tails of halfedges 3f, 3f+1, 3f+2) and their
/// cotangents, at scale factors u. Returns false when some face breaks the triangle inequality.
bool intrinsic_corner_angles(const IntrinsicTriangulation& tri, const Eigen::VectorXd& u,
                             Eigen::MatrixX3d& angles, Eigen::MatrixX3d* cotangents = nullptr);

/// Vertex curvature 2 pi - (angle sum) from corner angles.
[[nodiscard]] Eigen::VectorXd intrinsic_curvature(const IntrinsicTriangulation& tri,
                                                  const Eigen::MatrixX3d& angles);

/// Euler characteristic V - E + F.
[[nodiscard]] int euler_characteristic(const IntrinsicTriangulation& tri);

/// Whether every edge joins two distinct vertices and no two edges join the same pair (so the
/// triangulation is a simplicial complex an OpenMesh mesh can hold).
[[nodiscard]] bool is_simplicial(const IntrinsicTriangulation& tri);

/// The triangulation as a mesh (vertex positions from `positions`, #V by 3, e.g. the input's:
/// the vertices are the input's) and its edge lengths at u, by the mesh's edge index.
struct IntrinsicMesh {
  Mesh mesh;
  Eigen::VectorXd lengths;
};

/// \throw TopologyError when !is_simplicial(tri); InvalidInputError for a size mismatch.
[[nodiscard]] IntrinsicMesh to_mesh(const IntrinsicTriangulation& tri, const Eigen::VectorXd& u,
                                    const Eigen::MatrixX3d& positions);

/// to_mesh's mesh as tables (metric/mesh_tables.h), without the mesh: equal to
/// build_mesh_tables(to_mesh(tri, u, positions).mesh) (faces in the triangulation's order, edges
/// numbered as that mesh numbers them), for a long-double polish that runs before the mesh is
/// built (at 1.6M faces the tables are 61 MB, the mesh 136). \throw as to_mesh.
[[nodiscard]] MeshTables to_mesh_tables(const IntrinsicTriangulation& tri);

/// The lengths at u of the edges of to_mesh_tables(tri), by its edge index.
[[nodiscard]] Eigen::VectorXd table_edge_lengths(const IntrinsicTriangulation& tri,
                                                 const MeshTables& tables,
                                                 const Eigen::VectorXd& u);

/// The mesh of `tables` (to_mesh_tables' or build_mesh_tables' of a closed mesh; vertex
/// positions from `positions`), and `edge_of`: the mesh's edge index of each table edge.
/// \throw TopologyError when a face is not manifold; InvalidInputError for a size mismatch.
[[nodiscard]] Mesh mesh_of_tables(const MeshTables& tables, const Eigen::MatrixX3d& positions,
                                  std::vector<int>& edge_of);

/// Values by table edge moved to the mesh's edge edge_of[e] (mesh_of_tables); empty stays empty,
/// and an identity map (to_mesh_tables' tables) hands the values back as they are.
/// \throw InvalidInputError when the sizes differ.
[[nodiscard]] Eigen::VectorXd by_mesh_edge(Eigen::VectorXd by_table_edge,
                                           const std::vector<int>& edge_of);

}  // namespace ricci

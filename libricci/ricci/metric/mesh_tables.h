#pragma once
// Flat index tables of a triangle mesh's connectivity, built once so that the metric and flow
// loops run over plain arrays instead of OpenMesh circulators.
#include <vector>

#include <Eigen/Core>

#include "ricci/mesh/mesh.h"

namespace ricci {

/// Edge lengths of a discrete metric, indexed by OpenMesh edge index.
using EdgeLengths = Eigen::VectorXd;

/// Connectivity of a triangle mesh as index arrays.
struct MeshTables {
  /// #F by 3 vertex indices of each face, in the mesh's orientation.
  Eigen::MatrixX3i face_vertices;
  /// #F by 3 edge indices: face_edges(f, k) is the edge opposite face_vertices(f, k).
  Eigen::MatrixX3i face_edges;
  /// #E by 2 vertex indices of each edge (OpenMesh halfedge 0 of the edge: from, to).
  Eigen::MatrixX2i edge_vertices;
  /// 1 for vertices on a boundary loop, 0 otherwise.
  std::vector<char> is_boundary_vertex;
  /// Boundary loops as vertex index sequences (in the order the boundary halfedges run).
  std::vector<std::vector<int>> boundary_loops;
  /// Number of faces around each vertex.
  Eigen::VectorXi valence;
  /// Euler characteristic V - E + F.
  int euler_characteristic = 0;

  int num_vertices() const { return static_cast<int>(is_boundary_vertex.size()); }
  int num_edges() const { return static_cast<int>(edge_vertices.rows()); }
  int num_faces() const { return static_cast<int>(face_vertices.rows()); }
};

/// Builds the tables. \throw InvalidInputError for an empty mesh or a face that is not a
/// triangle; TopologyError for isolated vertices (they carry no metric).
[[nodiscard]] MeshTables build_mesh_tables(const Mesh& mesh);

/// Euclidean lengths of the mesh's edges in R^3, by edge index.
[[nodiscard]] EdgeLengths mesh_edge_lengths(const Mesh& mesh);

}  // namespace ricci

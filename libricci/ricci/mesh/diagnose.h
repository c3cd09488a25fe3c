#pragma once
// Describing a polygon soup: counts, topology (components, boundary loops, Euler characteristic,
// genus), manifoldness, orientability and defects, each defect with a one-line message saying
// where it is. Works on any soup, however broken; msp info prints it, build_mesh() enforces it.
#include <string>
#include <vector>

#include "ricci/mesh/soup.h"

namespace ricci {

/// The kinds of defect that keep a soup from being a clean single-component orientable
/// 2-manifold, in the order diagnose() reports them (the first one is the headline).
enum class MeshProblemKind {
  non_finite_coordinate,  ///< a referenced vertex has a NaN or infinite coordinate
  bad_face,               ///< fewer than 3 vertices or an index outside [0, #V)
  no_faces,               ///< nothing left to describe
  repeated_index,         ///< a face lists one vertex twice (degenerate)
  non_manifold_edge,      ///< an edge in more than 2 faces
  non_manifold_vertex,    ///< a vertex whose faces form several fans (pinched)
  non_orientable,         ///< no consistent orientation exists (Mobius strip, Klein bottle)
  duplicate_face,         ///< two faces on the same vertex set
  several_components,     ///< more than one connected component
  zero_area,              ///< a face of (numerically) zero area
};

/// One kind of defect: how many elements have it and a message naming the first of them.
struct MeshProblem {
  MeshProblemKind kind;
  int count = 0;
  std::string message;  ///< e.g. "edge (12, 40) is shared by 3 faces (faces 7, 9, 31)"
};

/// Everything diagnose() finds. Conventions (those of the INDEX.md tables of models/ and
/// tests/data/meshes/):
/// faces are the polygons as written (not triangulated; chi does not depend on it for manifold
/// polygons); faces with a bad or repeated index are left out of the topology; edges are the
/// distinct undirected polygon sides; chi = V - E + F counts referenced vertices only;
/// genus = (2c - b - chi) / 2, a half-integer when the mesh is not a 2-manifold.
struct MeshDiagnosis {
  int vertices = 0;               ///< vertices in the file
  int referenced_vertices = 0;    ///< vertices used by a face that enters the topology
  int unreferenced_vertices = 0;  ///< vertices no such face uses
  int edges = 0;
  int faces = 0;  ///< faces in the file
  int non_triangle_faces = 0;
  int components = 0;      ///< connected through shared vertices
  int boundary_edges = 0;  ///< edges in exactly one face
  int boundary_loops = 0;  ///< connected components of the boundary edges
  int euler_characteristic = 0;
  double genus = 0;             ///< (2c - b - chi) / 2
  bool edge_manifold = true;    ///< every edge in at most 2 faces
  bool vertex_manifold = true;  ///< the faces around each vertex form one fan
  bool orientable = true;       ///< the faces can be oriented consistently (over 2-face edges)
  bool consistently_oriented = true;  ///< no directed edge is used twice
  int non_manifold_edges = 0;
  int non_manifold_vertices = 0;
  int degenerate_faces = 0;           ///< repeated index, or area <= 1e-12 * (longest side)^2
  int duplicate_vertices = 0;         ///< vertices at exactly the position of an earlier one
  int duplicate_faces = 0;            ///< faces on the same vertex set as an earlier one
  int bad_faces = 0;                  ///< faces with < 3 vertices or an out-of-range index
  int non_finite_vertices = 0;        ///< vertices with a NaN or infinite coordinate
  double bbox_diagonal = 0;           ///< over the finite vertex positions
  double min_angle_deg = 0;           ///< smallest triangle angle (triangles only; 0 if none)
  std::vector<MeshProblem> problems;  ///< empty iff the soup is a clean surface (see below)

  /// The "clean manifold" column of INDEX.md: there are faces, every edge is in at most 2 faces,
  /// every vertex has one fan, orientable, and no repeated-index, duplicate or bad faces.
  [[nodiscard]] bool clean_manifold() const;
  /// What the pipeline needs: a single-component orientable 2-manifold with finite coordinates
  /// and no degenerate faces (duplicate positions, unreferenced vertices, polygons and
  /// inconsistent orientation are all fine: build_mesh() deals with them).
  [[nodiscard]] bool is_clean_surface() const { return problems.empty(); }
};

/// Describes any soup. Never throws on bad data: defects are counted and listed in `problems`.
[[nodiscard]] MeshDiagnosis diagnose(const PolygonSoup& soup);

}  // namespace ricci

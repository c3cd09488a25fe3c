#pragma once
// Turning a clean polygon soup into the library's ricci::Mesh.
#include <vector>

#include "ricci/mesh/mesh.h"
#include "ricci/mesh/soup.h"

namespace ricci {

/// A mesh built from a soup, with what was changed on the way.
struct MeshBuildResult {
  Mesh mesh;
  /// input_vertex[v] = index in the soup of mesh vertex v (unreferenced soup vertices dropped).
  std::vector<int> input_vertex;
  int unreferenced_removed = 0;   ///< soup vertices no face used
  int faces_flipped = 0;          ///< soup faces reversed to orient the surface consistently
  int polygons_triangulated = 0;  ///< soup faces of more than 3 vertices split by ear clipping
};

/// Builds a triangle mesh from a soup that diagnose() finds clean: polygons are ear-clipped in
/// their best-fit plane, unreferenced vertices dropped, faces flipped to one consistent
/// orientation (kept from the first face, or outward (positive volume) on closed surfaces).
/// \throw TopologyError (non-manifold, non-orientable, several components, no faces) or
///        InvalidInputError (non-finite coordinates, degenerate faces) with the first problem
///        diagnose() lists, as "<source>: <message>".
[[nodiscard]] MeshBuildResult build_mesh_with_report(const PolygonSoup& soup);

/// build_mesh_with_report(soup).mesh.
[[nodiscard]] Mesh build_mesh(const PolygonSoup& soup);

}  // namespace ricci

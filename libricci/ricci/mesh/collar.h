#pragma once
// A collar of ghost faces outside an open surface's boundary: the surface continued across its
// boundary loops by a few rings of triangles in its tangent planes. A spline over the collared
// mesh has its full set of basis functions on every face of the original surface (the partition
// of unity fails only within a ring or two of the domain's rim, now inside the collar), so the
// original faces can be fitted and tessellated up to their boundary and the collar dropped.
#include <vector>

#include "ricci/mesh/mesh.h"

namespace ricci {

struct CollarOptions {
  int rings = 2;  ///< Rings of ghost triangles added outside every boundary loop (>= 1).
  /// Width of each ring at a boundary vertex, as a fraction of the mean length of the two
  /// boundary edges there.
  double width = 0.8;
  /// ... and all rings together at most this fraction of the loop's radius (perimeter / 2 pi),
  /// so that the collar inside a small hole does not reach across it.
  double max_loop_fraction = 0.4;
};

struct CollarResult {
  Mesh mesh;  ///< The input's vertices and faces first (same indices), then the collar's.
  int original_vertices = 0, original_faces = 0;
  /// By face of `mesh`: 0 for the input's faces, k in 1..rings for the k-th ring outwards.
  std::vector<int> ring;
};

/// Adds `rings` rings of triangles outside every boundary loop of `mesh`: each boundary vertex v
/// gets a copy moved by `width` times its boundary edges' mean length along the outward
/// direction in its tangent plane (perpendicular to the boundary, away from the surface, averaged
/// with its loop neighbours'), and each boundary edge (a, b) the two triangles (a, b, b'),
/// (a, b', a'), each ring at most max_loop_fraction / rings of the loop's radius wide;
/// orientation and topology (genus, boundary loops) are kept. A closed mesh comes
/// back unchanged (no ring).
/// \pre an oriented 2-manifold triangle mesh.
/// \throw InvalidInputError for rings < 1 or width <= 0, or a boundary vertex on two boundary
///        loops' ends (a pinched boundary: the collar would not be a manifold).
[[nodiscard]] CollarResult add_boundary_collar(const Mesh& mesh, const CollarOptions& options = {});

}  // namespace ricci

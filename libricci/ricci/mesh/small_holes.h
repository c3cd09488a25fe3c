#pragma once
// Small holes of a scan capped: boundary loops far smaller than the resolution any fit of the
// scan is asked for (a missing triangle or two of a laser scan) are not boundaries a surface
// should reproduce. Left open, the spline domain carries a hole of a few short edges, and the
// fit folds around it.
#include <vector>

#include "ricci/mesh/mesh.h"

namespace ricci {

struct SmallHoleOptions {
  /// A boundary loop is capped when its diameter (the largest distance between two of its
  /// vertices) is below this fraction of the mesh's bounding-box diagonal; 0: none is.
  double max_diameter = 0.002;
};

struct SmallHoleCaps {
  Mesh mesh;  ///< The input's vertices and faces first (same indices), then the caps' faces.
  int capped_loops = 0;
  int cap_faces = 0;
  /// Largest diameter of a capped loop (fraction of the diagonal); 0 when none was capped.
  double largest_diameter = 0.0;
  /// By vertex of `mesh`: 1 on a capped loop (for leaving those loops out of a boundary
  /// comparison), 0 elsewhere.
  std::vector<char> capped_vertex;
};

/// Caps every boundary loop of `mesh` whose diameter is below options.max_diameter times the
/// bounding-box diagonal with triangles of its own vertices (ear clipping in the loop's plane,
/// ricci::triangulate_polygon; no vertex is added), oriented as the surface. A loop whose cap
/// would make an edge non-manifold (a diagonal that already is an edge) is left open. Genus is
/// kept; the boundary loops drop by capped_loops.
/// \pre an oriented 2-manifold triangle mesh.
/// \throw InvalidInputError for a max_diameter < 0 or not finite.
[[nodiscard]] SmallHoleCaps cap_small_holes(const Mesh& mesh, const SmallHoleOptions& options = {});

}  // namespace ricci

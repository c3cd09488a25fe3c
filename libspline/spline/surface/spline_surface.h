#pragma once
// The delivered surface of a scan fit: a manifold spline over its domain mesh plus the patches
// that cap its holes. It holds everything needed to evaluate and tessellate the surface again
// without refitting; spline_file.h saves and loads it.
#include <vector>

#include "ricci/mesh/mesh.h"
#include "spline/fill/hole_fill.h"
#include "spline/manifold/manifold_space.h"

namespace spline {

struct SplineSurface {
  /// The spline's domain mesh (the simplified, cone-refined scan the atlas was built on).
  ricci::Mesh domain;
  /// The spline over `domain`; its space holds the affine atlas (charts, transitions).
  ManifoldSpline spline;
  /// Domain vertex of the extraordinary point; -1 when there is none (tori, open surfaces).
  int singular_vertex = -1;
  /// The patches capping rims (the cone's hole, excluded faces, boundaries on request); each
  /// holds its rim.
  std::vector<HoleFill> fills;
  /// Rims left open on purpose (boundary loops not filled) or because their fill was refused.
  std::vector<Rim> open_rims;
  /// By domain face, nonzero: not tessellated (outside the spline's domain, or in the band a
  /// rim's patch covers). Empty: every domain face is tessellated.
  std::vector<char> skipped_faces;
};

}  // namespace spline

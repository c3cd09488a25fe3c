#pragma once
// Watertight tessellation of a SplineSurface: the spline over its tessellated domain faces
// (tessellate/tessellate.h) with every fill patch welded in along its rim
// (tessellate/tessellate_fill.h), so spline and patches are one welded surface.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "spline/fill/hole_fill.h"
#include "spline/surface/spline_surface.h"
#include "spline/tessellate/tessellate.h"

namespace spline {

/// Samples per domain edge - 1 giving about 120k triangles over `domain_faces` faces (smooth
/// shading at the zoom a viewer starts with), clamped to 2..8.
[[nodiscard]] int default_density(int domain_faces);

/// The spline sampled on every domain face not in surface.skipped_faces, then each of
/// surface.fills tessellated at the same density and welded to the spline's rim samples
/// (triangle_face -1 - i for fill i). options.skip_faces is replaced by surface.skipped_faces.
/// \pre surface.spline's space was built on surface.domain; every fill's rim borders the
/// tessellated faces (as fit_surface leaves them).
/// \throw ricci::InvalidInputError for density < 1, a skipped_faces or domain of another size,
///        or a fill whose rim is not on tessellated faces; as ManifoldSpline::evaluate.
[[nodiscard]] Tessellation tessellate_surface(const SplineSurface& surface,
                                              const TessellationOptions& options = {});

/// The same, also returning each fill's own tessellation (interior vertices with their
/// parameters in the patch's domain) in `patches`, one per fill.
[[nodiscard]] Tessellation tessellate_surface(const SplineSurface& surface,
                                              const TessellationOptions& options,
                                              std::vector<PatchTessellation>& patches);

/// A triangle soup: positions and triangles by position index.
struct TriangleSoup {
  Eigen::MatrixX3d positions;
  std::vector<std::array<int, 3>> triangles;
};

/// The tessellation as a file holds it: positions rounded to float and equal ones welded (a
/// glTF or PLY reader's view), triangles in tessellation order.
[[nodiscard]] TriangleSoup float_welded(const Tessellation& tessellation);

/// Topology of float_welded(tessellation).
[[nodiscard]] WatertightReport float_welded_topology(const Tessellation& tessellation);

}  // namespace spline

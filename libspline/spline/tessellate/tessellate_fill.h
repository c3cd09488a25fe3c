#pragma once
// Welding the hole-filling patches (fill/hole_fill.h) into a spline tessellation: the patch's rim
// samples ARE the tessellation's edge samples of the rim edges (same convention: t = i / d from
// the rim edge's start corner), so surface + patches are one closed welded surface.
#include "spline/fill/hole_fill.h"
#include "spline/tessellate/tessellate.h"

namespace spline {

/// Appends `patch` (tessellate_fill(fill, t.density)) to `t`: its interior vertices as new
/// positions (normals from the patch's exact derivatives), its triangles with rim samples
/// replaced by t's own samples of the rim edges (triangle_face -1 - patch_index). Texture
/// coordinates: the patch's domain D scaled to the surface's mean uv per unit length, in render
/// vertices of its own (a uv seam along the rim; the positions are shared).
/// \pre `t` was made with the rim's faces tessellated and the covered faces skipped.
/// \throw ricci::InvalidInputError when the patch was made at another density or refers to rim
///        samples outside the rim.
void append_fill(Tessellation& t, const HoleFill& fill, const PatchTessellation& patch,
                 int patch_index);

}  // namespace spline

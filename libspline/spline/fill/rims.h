#pragma once
// Rim finding on plain face masks (the work behind find_rims of hole_fill.h), for callers and
// tests that have a mesh and a domain but no spline space.
#include <functional>
#include <vector>

#include "ricci/mesh/mesh.h"
#include "spline/fill/hole_fill.h"

namespace spline {

/// Which holes a grown layer may merge.
struct RimMergeOptions {
  /// A boundary loop's hole with another hole (when the union is a disk). Off: such a layer is
  /// redone face by face, so every boundary loop keeps its own rim (for loops left open: the
  /// surface keeps the input's boundary loops, at the price of the band between two loops a
  /// ring apart, where the partition of unity fails).
  bool boundary_loops = true;
};

/// find_rims over masks by face: `domain` nonzero for the spline space's faces (kept before
/// growing), `atlas_domain` nonzero for the atlas' faces. Faces in neither are the cone's
/// one-ring (cone holes), faces in atlas_domain only are excluded faces; the mesh's boundary
/// loops are boundary holes.
///
/// Growing (FindRimsOptions::grow) never leaves a hole that a patch cannot close: after each
/// layer every hole (connected covered and outside faces plus the boundary loops they reach) is
/// a disk (Euler characteristic 1 with the loops capped) whose rim is one simple loop sharing
/// no vertex with another rim. Nearby holes whose grown layers meet merge into one hole when
/// the union is such a disk (the band between two boundary loops a ring apart; see
/// RimMergeOptions). Where a layer
/// breaks that (a hole grown around a handle, a hole touching itself or another hole at a
/// vertex), the layer is undone on that hole and redone face by face, taking a face only when
/// it keeps the hole a disk apart from every other hole.
/// `chart_scale` (chart_scale_by_face, or empty) and `normal_step_deg` (by face, e.g.
/// max_normal_step_deg of the fitted spline, or empty) drive the cone hole's extra layers
/// (FindRimsOptions::max_cone_rim_scale_ratio, max_cone_rim_normal_step_deg).
/// \throw ricci::InvalidInputError when a mask's or chart_scale's size is not the face count or
///        grow < 0.
[[nodiscard]] std::vector<Rim> find_rims(
    const ricci::Mesh& mesh, const std::vector<char>& domain,
    const std::vector<char>& atlas_domain, const FindRimsOptions& options = {},
    const RimMergeOptions& merge = {}, const std::vector<double>& chart_scale = {},
    const std::function<double(int face)>& normal_step_deg = {});

}  // namespace spline

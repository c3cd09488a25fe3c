#pragma once
// The picture of a one-cone atlas (issue 4): the fundamental domain in the central chart with
// its triangles, the cut sides coloured and named per loop with gluing arrows, the cone's
// one-ring shaded, and around it copies of the domain moved by the side-pairing motions (a patch
// of the universal cover), with a caption saying what is drawn.
#include <string>

#include <ricci/pipeline/one_cone_atlas.h>

namespace msp {

struct AtlasSvgOptions {
  std::string title;       ///< First caption line, e.g. the mesh file.
  double width_px = 1000;  ///< Width of the SVG in pixels.
  /// Copies are products of up to this many side pairings; -1: 2 on a torus (translations tile
  /// the plane), 1 otherwise (the first ring: more would pile up around the cone).
  int cover_depth = -1;
  /// The view is the domain's bounding box grown by this fraction of its size on each side.
  double view_margin = 0.6;
};

/// The SVG document (UTF-8 text).
/// \throw ricci::InvalidInputError if the result holds no atlas (empty layout).
[[nodiscard]] std::string atlas_svg(const ricci::OneConeAtlasResult& result,
                                    const AtlasSvgOptions& options = {});

/// The depth `atlas_svg` uses for `options.cover_depth` (resolves -1).
[[nodiscard]] int resolved_cover_depth(const ricci::OneConeAtlasResult& result, int cover_depth);

}  // namespace msp

#pragma once
// The picture of a uniformization (issue 7): for genus >= 2 the Poincaré disk with the
// fundamental domain (the tree-cotree disk, its sides coloured by loop) and its images under
// the side-pairing maps of word length <= depth (a few rings of the universal cover); for a torus
// the flat domain and its translates; for a sphere the embedding seen from outside.
#include <string>

#include <ricci/hyperbolic/uniformize.h>

namespace msp {

struct PoincareSvgOptions {
  std::string title;       ///< First caption line, e.g. the mesh file.
  double width_px = 1000;  ///< Width of the drawing in pixels.
  /// Copies are products of up to this many side pairings (arc pairings and their inverses).
  int depth = 5;
  /// Copies whose picture spans fewer pixels than this are not drawn.
  double min_copy_px = 1.5;
  int max_copies = 6000;
};

/// What the picture holds, for the caption and the tests.
struct PoincareSvgStats {
  int copies_drawn = 0;  ///< Including the central domain.
  int copies_culled = 0;  ///< Smaller than min_copy_px.
};

/// The SVG document (UTF-8 text).
/// \throw ricci::InvalidInputError if the uniformization did not converge.
[[nodiscard]] std::string uniformization_svg(const ricci::Uniformization& u,
                                             const PoincareSvgOptions& options = {},
                                             PoincareSvgStats* stats = nullptr);

}  // namespace msp

#pragma once
// The picture of a conformal module's canonical domain (issue 17): the annulus r < |z| < 1, the
// rectangle of width 1, the flat torus's parallelogram or the Poincaré-disk fundamental domain,
// with the mesh's triangles, the boundary loops coloured, the rectangle's corners, and a caption
// giving the module.
#include <string>

#include <ricci/analysis/conformal_module.h>

namespace msp {

struct ModuleSvgOptions {
  std::string title;       ///< First caption line, e.g. the mesh file.
  double width_px = 1000;  ///< Width of the SVG in pixels.
  /// Triangle edges are drawn up to this many faces (beyond, they merge into grey).
  int max_drawn_edges_faces = 60000;
};

/// The SVG document (UTF-8 text).
/// \throw ricci::InvalidInputError when the result has no domain (a sphere, or no convergence).
[[nodiscard]] std::string module_svg(const ricci::ModuleResult& result,
                                     const ModuleSvgOptions& options = {});

/// "module 0.1458" / "re_tau 0.0312, im_tau 1.204": the module's values with their names.
[[nodiscard]] std::string module_values_text(const ricci::ModuleResult& result);

}  // namespace msp

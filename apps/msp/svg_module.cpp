#include "msp/svg_module.h"

#include <cstdio>

#include <ricci/mesh/errors.h>

#include "msp/svg_canvas.h"
#include "msp/svg_cover.h"

namespace msp {

namespace {

std::string what_is_drawn(ricci::ModuleKind kind) {
  switch (kind) {
    case ricci::ModuleKind::Annulus:
      return "flat metric with geodesic boundaries, cut open and carried by exp to the annulus "
             "r < |z| < 1";
    case ricci::ModuleKind::Rectangle:
      return "flat metric with right-angled corners: the rectangle of width 1 (corners dotted)";
    case ricci::ModuleKind::FlatTorus:
      return "fundamental domain of the flat torus, first translation = 1";
    case ricci::ModuleKind::CircleDomain:
      return "flat metric with round boundaries, laid out and Mobius-normalised: c0 the unit "
             "circle, c1 centred at 0, c2 on the positive real axis";
    case ricci::ModuleKind::Fuchsian:
      return "fundamental domain in the Poincare disk";
    case ricci::ModuleKind::Disk:
      return "flat metric with a round boundary: the conformal map onto the unit disk, the centre "
             "vertex at 0 (dotted) and the boundary vertex nearest it at 1";
    case ricci::ModuleKind::Hyperbolic:
      return "hyperbolic metric with geodesic boundaries (coloured by loop), cut to a disk, in the "
             "Poincare disk";
    default:
      return "the mesh laid out in its canonical domain";
  }
}

}  // namespace

std::string module_values_text(const ricci::ModuleResult& result) {
  std::string text;
  for (size_t i = 0; i < result.values.size(); ++i) {
    char number[64];
    std::snprintf(number, sizeof number, "%.6g", result.values[i]);
    text += (i ? ", " : "") + result.names[i] + " " + number;
  }
  return text.empty() ? "no module" : text;
}

std::string module_svg(const ricci::ModuleResult& result, const ModuleSvgOptions& options) {
  const ricci::CanonicalDomain& domain = result.domain;
  if (domain.positions.rows() == 0) {
    throw ricci::InvalidInputError("the " + ricci::to_string(result.kind) +
                                   " module has no canonical domain to draw");
  }
  Eigen::AlignedBox2d view(domain.positions.colwise().minCoeff().transpose(),
                           domain.positions.colwise().maxCoeff().transpose());
  const bool disk =
      result.kind == ricci::ModuleKind::Fuchsian || result.kind == ricci::ModuleKind::Hyperbolic;
  if (disk) view = Eigen::AlignedBox2d(Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1));
  const Eigen::Vector2d grow = 0.05 * view.sizes();
  view = Eigen::AlignedBox2d(view.min() - grow, view.max() + grow);
  SvgCanvas canvas(view, options.width_px);
  if (disk) {
    const Eigen::Vector2d c = canvas.px(Eigen::Vector2d(0, 0));
    canvas.add("<circle cx=\"" + svg_number(c.x()) + "\" cy=\"" + svg_number(c.y()) + "\" r=\"" +
               svg_number(canvas.pixels_per_unit()) +
               "\" fill=\"none\" stroke=\"#444\" stroke-width=\"1.5\"/>");
  }
  std::string triangles;
  Eigen::MatrixX2d tri(3, 2);
  for (Eigen::Index f = 0; f < domain.faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) tri.row(k) = domain.positions.row(domain.faces(f, k));
    triangles += canvas.path_data(tri, true);
  }
  const bool edges = domain.faces.rows() <= options.max_drawn_edges_faces;
  canvas.add("<path d=\"" + triangles + "\" fill=\"#5b7fa6\" fill-opacity=\"0.25\" stroke=\"" +
             (edges ? "#5b7fa6\" stroke-opacity=\"0.6\" stroke-width=\"0.3\"" : "none\"") +
             " stroke-linejoin=\"round\"/>");
  for (size_t b = 0; b < domain.boundaries.size(); ++b) {
    const std::vector<int>& loop = domain.boundaries[b];
    Eigen::MatrixX2d points(static_cast<Eigen::Index>(loop.size()), 2);
    for (size_t i = 0; i < loop.size(); ++i) points.row(i) = domain.positions.row(loop[i]);
    canvas.add("<path d=\"" + canvas.path_data(points, loop.size() > 2) +
               "\" fill=\"none\" stroke=\"" + loop_colour_hex(domain.boundary_loop[b]) +
               "\" stroke-width=\"2\"/>");
  }
  for (int c : domain.corners) {
    const Eigen::Vector2d p = canvas.px(domain.positions.row(c).transpose());
    canvas.add("<circle cx=\"" + svg_number(p.x()) + "\" cy=\"" + svg_number(p.y()) +
               "\" r=\"5\" fill=\"#d62728\"/>");
  }
  const std::vector<std::string> caption = {
      options.title,
      ricci::to_string(result.kind) + " module (genus " + std::to_string(result.genus) + ", " +
          std::to_string(result.boundary_loops) + " boundary loops): " +
          module_values_text(result),
      what_is_drawn(result.kind)};
  return captioned_svg(canvas, caption, 13);
}

}  // namespace msp

#include "msp/svg_atlas.h"

#include <cmath>
#include <cstdio>

#include <ricci/mesh/errors.h>

#include "msp/svg_canvas.h"
#include "msp/svg_cover.h"

namespace msp {
namespace {

const char* const kConeFill = "#ffa31a";

std::string loop_colour(int loop) { return loop_colour_hex(loop); }

std::string fixed(double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

/// Names of the cut sides: the loop's name, or t1, t2, ... for arcs of the tree part.
std::vector<std::string> side_names(const ricci::AffineAtlas& atlas,
                                    const std::vector<std::string>& loops) {
  std::vector<std::string> names;
  int tree = 0;
  for (const auto& side : atlas.side_pairings) {
    names.push_back(side.loop >= 0 ? loops[static_cast<size_t>(side.loop)]
                                   : "t" + std::to_string(++tree));
  }
  return names;
}

std::string word_text(const ricci::FundamentalPolygon& polygon,
                      const std::vector<std::string>& loops) {
  std::string text;
  for (const auto& letter : polygon.word) {
    if (!text.empty()) text += ' ';
    text += letter.kind == ricci::PolygonLetter::Kind::loop
                ? loops[static_cast<size_t>(letter.index)]
                : "∂" + std::to_string(letter.index + 1);
    if (letter.sign < 0) text += "⁻¹";
  }
  return text;
}

/// The point at `fraction` of a polyline's length.
Eigen::Vector2d point_along(const Eigen::MatrixX2d& p, double fraction) {
  double total = 0.0;
  for (Eigen::Index i = 0; i + 1 < p.rows(); ++i) total += (p.row(i + 1) - p.row(i)).norm();
  double walked = 0.0;
  for (Eigen::Index i = 0; i + 1 < p.rows(); ++i) {
    const Eigen::Vector2d a = p.row(i).transpose(), b = p.row(i + 1).transpose();
    const double len = (b - a).norm();
    if (walked + len >= fraction * total && len > 0)
      return a + (fraction * total - walked) / len * (b - a);
    walked += len;
  }
  return p.row(p.rows() - 1).transpose();
}

/// Point halfway along a polyline and its direction there, smoothed over the middle fifth (cut
/// paths follow mesh edges and zigzag).
std::pair<Eigen::Vector2d, Eigen::Vector2d> midpoint(const Eigen::MatrixX2d& p) {
  Eigen::Vector2d chord = point_along(p, 0.6) - point_along(p, 0.4);
  if (chord.norm() == 0) chord = p.row(p.rows() - 1).transpose() - p.row(0).transpose();
  if (chord.norm() == 0) chord = Eigen::Vector2d(1, 0);
  return {point_along(p, 0.5), chord.normalized()};
}

/// The angle that turns the domain's principal axis horizontal: the picture is defined up to a
/// rigid motion, and a long domain reads better lying down.
double display_rotation(const Eigen::MatrixX2d& outline) {
  const Eigen::MatrixX2d centred = outline.rowwise() - outline.colwise().mean();
  const Eigen::Matrix2d c = centred.transpose() * centred;
  const double axis = 0.5 * std::atan2(2 * c(0, 1), c(0, 0) - c(1, 1));
  return -axis;
}

/// The view: the domain's box grown by `margin` on each side, cut to what is drawn, with an
/// aspect ratio (height / width) kept in [0.55, 1.3] so the picture reads well at 1000 px.
Eigen::AlignedBox2d fitted_view(const Eigen::MatrixX2d& outline,
                                const std::vector<Eigen::MatrixX2d>& copies, double margin) {
  // Both in the display frame.
  Eigen::AlignedBox2d domain(outline.colwise().minCoeff().transpose(),
                             outline.colwise().maxCoeff().transpose());
  Eigen::AlignedBox2d content = domain;
  for (const auto& c : copies) {
    content.extend(Eigen::Vector2d(c.colwise().minCoeff().transpose()));
    content.extend(Eigen::Vector2d(c.colwise().maxCoeff().transpose()));
  }
  const Eigen::Vector2d grow = margin * domain.sizes();
  Eigen::AlignedBox2d view(domain.min() - grow, domain.max() + grow);
  view = view.intersection(content);
  Eigen::Vector2d size = view.sizes();
  const Eigen::Vector2d centre = view.center();
  if (size.y() > 1.3 * size.x()) size.x() = size.y() / 1.3;
  if (size.y() < 0.55 * size.x()) size.y() = 0.55 * size.x();
  return {centre - 0.5 * size, centre + 0.5 * size};
}

struct Picture {
  const ricci::OneConeAtlasResult& result;
  const ricci::AffineAtlas& atlas;
  DomainOutline outline;
  std::vector<CutSide> sides;
  std::vector<std::string> names;
  std::vector<ricci::RigidMotion2> copies;
  std::vector<int> cone_faces;  ///< Faces outside the spline domain (the cone's one-ring).
  bool edges_drawn = false;     ///< Triangle edges are left out when they would merge into grey.
  double cone_ring = 0.0;       ///< Diameter of the cone's one-ring in the chart.
};

std::string triangle_path(const SvgCanvas& canvas, const ricci::AffineAtlas& atlas,
                          const std::vector<int>& faces, const ricci::RigidMotion2& motion) {
  std::string d;
  for (int f : faces) {
    Eigen::MatrixX2d tri(3, 2);
    int k = 0;
    for (auto v : atlas.sliced.mesh.fv_range(atlas.sliced.mesh.face_handle(f))) {
      tri.row(k++) = atlas.layout.positions.row(v.idx());
    }
    d += canvas.path_data(transformed(tri, motion), true);
  }
  return d;
}

void draw_copies(SvgCanvas& canvas, const Picture& pic) {
  canvas.add("<g id=\"copies\" stroke-linejoin=\"round\" stroke-linecap=\"round\">");
  for (const auto& motion : pic.copies) {
    canvas.add("<g class=\"copy\">");
    canvas.add("<path d=\"" + canvas.path_data(transformed(pic.outline.points, motion), true) +
               "\" fill=\"#5b7fa6\" fill-opacity=\"0.10\" stroke=\"#5b7fa6\" "
               "stroke-opacity=\"0.35\" stroke-width=\"0.8\"/>");
    if (!pic.cone_faces.empty()) {
      canvas.add("<path d=\"" + triangle_path(canvas, pic.atlas, pic.cone_faces, motion) +
                 "\" fill=\"" + kConeFill + "\" fill-opacity=\"0.30\" stroke=\"none\"/>");
    }
    for (const auto& side : pic.sides) {
      const int loop = pic.atlas.side_pairings[static_cast<size_t>(side.pairing)].loop;
      canvas.add("<path d=\"" + canvas.path_data(transformed(side.points, motion), false) +
                 "\" fill=\"none\" stroke=\"" + loop_colour(loop) +
                 "\" stroke-opacity=\"0.45\" stroke-width=\"1.3\"/>");
    }
    canvas.add("</g>");
  }
  canvas.add("</g>");
}

void draw_domain(SvgCanvas& canvas, Picture& pic) {
  const ricci::Mesh& sliced = pic.atlas.sliced.mesh;
  const Eigen::MatrixX2d& x = pic.atlas.layout.positions;
  double total = 0.0;
  for (auto e : sliced.edges()) {
    const auto h = sliced.halfedge_handle(e, 0);
    total += (x.row(sliced.from_vertex_handle(h).idx()) - x.row(sliced.to_vertex_handle(h).idx()))
                 .norm();
  }
  const double mean_px =
      total / static_cast<double>(std::max<size_t>(sliced.n_edges(), 1)) * canvas.pixels_per_unit();
  pic.edges_drawn = mean_px >= 2.5;
  std::string edges;
  Eigen::MatrixX2d segment(2, 2);
  for (auto e : sliced.edges()) {
    if (!pic.edges_drawn) break;
    const auto h = sliced.halfedge_handle(e, 0);
    segment.row(0) = x.row(sliced.from_vertex_handle(h).idx());
    segment.row(1) = x.row(sliced.to_vertex_handle(h).idx());
    edges += canvas.path_data(segment, false);
  }
  const double stroke = mean_px < 6 ? 0.25 : 0.4;
  canvas.add("<g id=\"domain\">");
  canvas.add("<path d=\"" + canvas.path_data(pic.outline.points, true) +
             "\" fill=\"#fffdf4\" fill-opacity=\"0.55\" stroke=\"none\"/>");
  if (!pic.cone_faces.empty()) {
    canvas.add("<path id=\"cone-one-ring\" d=\"" +
               triangle_path(canvas, pic.atlas, pic.cone_faces, {}) + "\" fill=\"" + kConeFill +
               "\" fill-opacity=\"0.75\" stroke=\"none\"/>");
  }
  if (pic.edges_drawn) {
    canvas.add("<path id=\"triangles\" d=\"" + edges +
               "\" fill=\"none\" stroke=\"#8a9099\" stroke-width=\"" + fixed(stroke, 2) +
               "\" stroke-opacity=\"0.9\"/>");
  }
  // Original boundary loops (open surfaces) in black: they are sides of the polygon too.
  canvas.add("<path d=\"" + canvas.path_data(pic.outline.points, true) +
             "\" fill=\"none\" stroke=\"#111\" stroke-width=\"1.2\"/>");
  canvas.add("</g>");
}

void draw_sides(SvgCanvas& canvas, const Picture& pic) {
  canvas.add(
      "<g id=\"cut-sides\" stroke-linejoin=\"round\" stroke-linecap=\"round\" font-family=\"DejaVu "
      "Sans, sans-serif\">");
  const double unit = 1.0 / canvas.pixels_per_unit();  // world length of one pixel
  for (const auto& side : pic.sides) {
    const auto& pairing = pic.atlas.side_pairings[static_cast<size_t>(side.pairing)];
    const std::string colour = loop_colour(pairing.loop);
    canvas.add("<path d=\"" + canvas.path_data(side.points, false) + "\" fill=\"none\" stroke=\"" +
               colour + "\" stroke-width=\"" + (pairing.loop >= 0 ? "2.6" : "1.8") + "\"/>");
    auto [mid, tangent] = midpoint(side.points);
    // The domain lies left of the arc's direction on the left side, right of it on the right side.
    const Eigen::Vector2d inward =
        (side.left ? 1.0 : -1.0) * Eigen::Vector2d(-tangent.y(), tangent.x());
    Eigen::MatrixX2d arrow(3, 2);
    arrow.row(0) = (mid + 7 * unit * tangent).transpose();
    arrow.row(1) = (mid - 5 * unit * tangent + 4.5 * unit * inward).transpose();
    arrow.row(2) = (mid - 5 * unit * tangent - 4.5 * unit * inward).transpose();
    canvas.add("<path d=\"" + canvas.path_data(arrow, true) + "\" fill=\"" + colour +
               "\" stroke=\"none\"/>");
    const Eigen::Vector2d at = canvas.px(mid + 15 * unit * inward);
    const std::string& name = pic.names[static_cast<size_t>(side.pairing)];
    canvas.add("<text x=\"" + svg_number(at.x()) + "\" y=\"" + svg_number(at.y() + 5) +
               "\" font-size=\"" + (pairing.loop >= 0 ? "16" : "11") +
               "\" font-weight=\"bold\" text-anchor=\"middle\" fill=\"" + colour +
               "\" stroke=\"#ffffff\" stroke-width=\"3\" paint-order=\"stroke\">" +
               svg_escape(name) + "</text>");
  }
  canvas.add("</g>");
}

// Copies of the cone on the polygon's corners, as dots: its one-ring is often too small to see
// (the flat metric's conformal factor vanishes at a cone of angle > 2 pi).
void draw_cone_copies(SvgCanvas& canvas, Picture& pic) {
  if (!pic.atlas.root_is_cone) return;
  const int root = pic.atlas.cut.root.idx();
  // The one-ring splits into wedges at the cone's copies; twice the largest face tells its size.
  double widest = 0.0;
  for (int f : pic.cone_faces) {
    Eigen::AlignedBox2d wedge;
    for (auto v : pic.atlas.sliced.mesh.fv_range(pic.atlas.sliced.mesh.face_handle(f))) {
      wedge.extend(Eigen::Vector2d(pic.atlas.layout.positions.row(v.idx()).transpose()));
    }
    widest = std::max(widest, wedge.diagonal().norm());
  }
  pic.cone_ring = 2.0 * widest;
  canvas.add("<g id=\"cone-copies\" fill=\"" + std::string(kConeFill) +
             "\" stroke=\"#111\" stroke-width=\"1.2\">");
  for (int v : pic.outline.vertices) {
    if (pic.atlas.sliced.to_original_vertex[static_cast<size_t>(v)] != root) continue;
    const Eigen::Vector2d p = canvas.px(pic.atlas.layout.positions.row(v).transpose());
    canvas.add("<circle cx=\"" + svg_number(p.x()) + "\" cy=\"" + svg_number(p.y()) +
               "\" r=\"4.5\"/>");
  }
  canvas.add("</g>");
}

std::vector<std::string> caption(const Picture& pic, const AtlasSvgOptions& options, int depth) {
  const auto& r = pic.result;
  const auto& mesh = r.problem.mesh;
  std::vector<std::string> lines;
  lines.push_back(options.title);
  std::string topology = "genus " + std::to_string(r.problem.genus);
  if (r.problem.boundary_loops > 0)
    topology += ", " + std::to_string(r.problem.boundary_loops) + " boundary loops";
  topology += " · " + std::to_string(mesh.n_vertices()) + " vertices, " +
              std::to_string(mesh.n_faces()) + " faces";
  if (r.problem.valence_splits > 0)
    topology += " (" + std::to_string(r.problem.valence_splits) + " valence splits)";
  if (!pic.edges_drawn) topology += " · triangles too small to draw";
  if (r.problem.kind == ricci::OneConeKind::PuncturedSphere) {
    topology += " · flat, punctured at input vertex " + std::to_string(r.chosen_vertex) +
                " (its star removed)";
  } else if (r.problem.cone < 0) {
    topology += " · flat, no cone";
  }
  if (r.problem.kind == ricci::OneConeKind::PuncturedSphere || r.problem.boundary_loops > 0) {
    topology += " · boundary in black";
  }
  lines.push_back(topology);
  if (r.problem.cone >= 0) {
    const double angle = 2 * M_PI - r.flow.curvature[r.problem.cone];
    char ring[32];
    std::snprintf(ring, sizeof ring, "%.1e",
                  pic.cone_ring / std::max(pic.atlas.domain_diameter, 1e-300));
    lines.push_back(
        "one cone of angle " + fixed(angle / M_PI, 2) +
        "π: orange dots; its one-ring (outside the spline domain, orange) spans about " + ring +
        " of the domain's diameter");
  }
  const auto loops = loop_names(pic.atlas);
  lines.push_back(
      "boundary word: " + word_text(pic.atlas.polygon, loops) +
      (pic.atlas.polygon.canonical ? " (canonical)" : " (not canonical: loops c1, c2, ...)"));
  lines.push_back(
      "sides of the same name are glued, arrows matching; grey t-sides: tree arcs shared by loops");
  std::string copies = std::to_string(pic.copies.size()) + " copies (blue) of the domain moved by ";
  if (pic.copies.empty()) {
    copies = "no copies: every side pairing is the identity (the cut is a slit of a flat disk)";
  } else if (depth == 1) {
    copies += "each side pairing and its inverse: first ring only";
    if (r.problem.cone >= 0) copies += "; they overlap around the cone by construction";
    if (r.problem.cone < 0 && r.problem.genus != 1)
      copies += "; they may overlap (rotations about the boundary loops)";
  } else {
    copies += "products of up to " + std::to_string(depth) + " side pairings";
    if (r.problem.cone < 0 && r.problem.genus == 1) copies += ": translations tiling the plane";
  }
  lines.push_back(copies);
  return lines;
}

}  // namespace

int resolved_cover_depth(const ricci::OneConeAtlasResult& result, int cover_depth) {
  if (cover_depth >= 0) return cover_depth;
  return result.problem.genus == 1 && result.problem.boundary_loops == 0 ? 2 : 1;
}

std::string atlas_svg(const ricci::OneConeAtlasResult& result, const AtlasSvgOptions& options) {
  const ricci::AffineAtlas& atlas = result.atlas;
  if (atlas.layout.positions.rows() == 0)
    throw ricci::InvalidInputError("atlas picture: the result has no layout");
  Picture pic{result, atlas, domain_outline(atlas), cut_sides(result.problem.mesh, atlas), {},
              {},     {}};
  pic.names = side_names(atlas, loop_names(atlas));
  const int depth = resolved_cover_depth(result, options.cover_depth);
  pic.copies = cover_motions(atlas, depth);
  for (size_t f = 0; f < atlas.in_domain.size(); ++f) {
    if (!atlas.in_domain[f]) pic.cone_faces.push_back(static_cast<int>(f));
  }
  ricci::RigidMotion2 display;
  display.angle = display_rotation(pic.outline.points);
  std::vector<Eigen::MatrixX2d> copy_outlines;
  for (const auto& m : pic.copies)
    copy_outlines.push_back(transformed(pic.outline.points, display.after(m)));

  SvgCanvas canvas(
      fitted_view(transformed(pic.outline.points, display), copy_outlines, options.view_margin),
      options.width_px, display.angle);
  draw_copies(canvas, pic);
  draw_domain(canvas, pic);
  draw_sides(canvas, pic);
  draw_cone_copies(canvas, pic);

  const std::vector<std::string> lines = caption(pic, options, depth);
  return captioned_svg(canvas, lines, 13);
}

}  // namespace msp

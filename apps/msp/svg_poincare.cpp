#include "msp/svg_poincare.h"

#include <algorithm>
#include <cmath>

#include <ricci/hyperbolic/universal_cover.h>
#include <ricci/mesh/errors.h>
#include <ricci/topology/cut_graph.h>

#include "msp/svg_canvas.h"
#include "msp/svg_cover.h"

namespace msp {
namespace {

using ricci::Complex;

Eigen::MatrixX2d to_rows(const std::vector<Complex>& z) {
  Eigen::MatrixX2d p(static_cast<Eigen::Index>(z.size()), 2);
  for (size_t i = 0; i < z.size(); ++i) p.row(static_cast<Eigen::Index>(i)) << z[i].real(), z[i].imag();
  return p;
}

/// Drops points closer than `spacing` to the last kept one (the picture cannot show them).
std::vector<Complex> thinned(const std::vector<Complex>& z, double spacing) {
  std::vector<Complex> out;
  for (const Complex& p : z) {
    if (out.empty() || std::abs(p - out.back()) >= spacing) out.push_back(p);
  }
  return out;
}

/// The sliced disk's boundary as positions, counter-clockwise.
std::vector<Complex> outline(const ricci::Uniformization& u) {
  const auto loops = ricci::find_boundary_loops(u.sliced.mesh);
  std::vector<Complex> z;
  if (loops.empty()) return z;
  // Boundary halfedges run clockwise around the disk; reverse for counter-clockwise.
  for (auto it = loops[0].rbegin(); it != loops[0].rend(); ++it) {
    z.push_back(u.positions[u.sliced.mesh.to_vertex_handle(*it).idx()]);
  }
  return z;
}

/// Both copies of every arc as polylines, with the arc's loop (-1: tree arc).
struct ArcSide {
  std::vector<Complex> points;
  int loop = -1;
};

std::vector<ArcSide> arc_sides(const ricci::Uniformization& u) {
  std::vector<ArcSide> sides;
  const auto& sm = u.sliced.mesh;
  for (const ricci::CutArc& arc : u.pairings.arcs) {
    for (int side = 0; side < 2; ++side) {
      ArcSide s;
      s.loop = arc.loop;
      for (auto h : arc.halfedges) {
        const ricci::HalfedgeHandle orig = side == 0 ? h : u.surface.opposite_halfedge_handle(h);
        const ricci::HalfedgeHandle sh(u.sliced.from_original_halfedge[orig.idx()]);
        const Complex a = u.positions[sm.from_vertex_handle(sh).idx()];
        const Complex b = u.positions[sm.to_vertex_handle(sh).idx()];
        if (side == 0) {
          if (s.points.empty()) s.points.push_back(a);
          s.points.push_back(b);
        } else {
          if (s.points.empty()) s.points.push_back(b);
          s.points.push_back(a);
        }
      }
      sides.push_back(std::move(s));
    }
  }
  return sides;
}

std::vector<Complex> mapped(const ricci::Mobius& g, const std::vector<Complex>& z) {
  std::vector<Complex> out;
  out.reserve(z.size());
  for (const Complex& p : z) out.push_back(g(p));
  return out;
}

double extent(const std::vector<Complex>& z) {
  double lo_x = INFINITY, hi_x = -INFINITY, lo_y = INFINITY, hi_y = -INFINITY;
  for (const Complex& p : z) {
    lo_x = std::min(lo_x, p.real());
    hi_x = std::max(hi_x, p.real());
    lo_y = std::min(lo_y, p.imag());
    hi_y = std::max(hi_y, p.imag());
  }
  return std::max(hi_x - lo_x, hi_y - lo_y);
}

const char* kShades[] = {"#fdf6e3", "#dfe9f5", "#e9f3df", "#f5e4df"};

/// The domain and its images (H2 or E2): fills by word length, outlines, coloured sides.
void draw_cover(SvgCanvas& canvas, const ricci::Uniformization& u, const PoincareSvgOptions& o,
                PoincareSvgStats& stats) {
  std::vector<ricci::Mobius> pairings;
  for (const auto& a : u.pairings.arcs) pairings.push_back(a.pairing);
  const std::vector<Complex> domain = outline(u);
  const std::vector<ArcSide> sides = arc_sides(u);
  const double px = 1.0 / canvas.pixels_per_unit();
  // Copies below min_copy_px are neither drawn nor extended: their neighbours further out are
  // smaller still, and the budget goes to the copies one can see.
  const auto visible = [&](const ricci::Mobius& g) {
    if (extent(mapped(g, domain)) >= o.min_copy_px * px) return true;
    ++stats.copies_culled;
    return false;
  };
  const auto elements = ricci::group_elements(pairings, o.depth, 1e-7, o.max_copies, visible);
  canvas.add("<g id=\"copies\" stroke-linejoin=\"round\">");
  // Far copies first, so the central domain is drawn last, on top.
  for (auto it = elements.rbegin(); it != elements.rend(); ++it) {
    const std::vector<Complex> image = mapped(it->map, domain);
    ++stats.copies_drawn;
    const double width = it->word_length == 0 ? 1.6 : std::max(0.3, 1.0 - 0.25 * it->word_length);
    canvas.add("<path d=\"" + canvas.path_data(to_rows(thinned(image, 0.4 * px)), true) +
               "\" fill=\"" + kShades[it->word_length % 4] + "\" stroke=\"#555\" stroke-width=\"" +
               std::to_string(width).substr(0, 4) + "\"/>");
    if (it->word_length > 1) continue;
    for (const ArcSide& s : sides) {
      canvas.add("<path d=\"" + canvas.path_data(to_rows(thinned(mapped(it->map, s.points), 0.4 * px)), false) +
                 "\" fill=\"none\" stroke=\"" + loop_colour_hex(s.loop) + "\" stroke-width=\"" +
                 (it->word_length == 0 ? "3" : "1.5") + "\"/>");
    }
  }
  canvas.add("</g>");
  // The triangles of the central domain, faint.
  std::string edges;
  const auto& sm = u.sliced.mesh;
  for (auto e : sm.edges()) {
    const auto h = sm.halfedge_handle(e, 0);
    const Complex a = u.positions[sm.from_vertex_handle(h).idx()];
    const Complex b = u.positions[sm.to_vertex_handle(h).idx()];
    edges += canvas.path_data(to_rows({a, b}), false) + " ";
  }
  canvas.add("<path id=\"triangles\" d=\"" + edges +
             "\" fill=\"none\" stroke=\"#999\" stroke-opacity=\"0.35\" stroke-width=\"0.3\"/>");
  for (const ArcSide& s : sides) {
    canvas.add("<path d=\"" + canvas.path_data(to_rows(s.points), false) + "\" fill=\"none\" stroke=\"" +
               loop_colour_hex(s.loop) + "\" stroke-width=\"3\"/>");
  }
}

/// The sphere from outside (orthographic, looking down -z): the front faces.
void draw_sphere(SvgCanvas& canvas, const ricci::Uniformization& u) {
  canvas.add("<circle cx=\"" + svg_number(canvas.px({0, 0}).x()) + "\" cy=\"" +
             svg_number(canvas.px({0, 0}).y()) + "\" r=\"" + svg_number(canvas.pixels_per_unit()) +
             "\" fill=\"#eef3f8\" stroke=\"#333\" stroke-width=\"1.5\"/>");
  std::string front;
  for (auto f : u.surface.faces()) {
    Eigen::Vector3d p[3];
    int k = 0;
    for (auto v : u.surface.fv_range(f)) p[k++] = u.sphere.positions.row(v.idx());
    if ((p[1] - p[0]).cross(p[2] - p[0]).z() <= 0) continue;
    Eigen::MatrixX2d tri(3, 2);
    for (int i = 0; i < 3; ++i) tri.row(i) << p[i].x(), p[i].y();
    front += canvas.path_data(tri, true) + " ";
  }
  canvas.add("<path id=\"front-faces\" d=\"" + front +
             "\" fill=\"none\" stroke=\"#345\" stroke-opacity=\"0.6\" stroke-width=\"0.4\"/>");
}

std::vector<std::string> caption(const ricci::Uniformization& u, const PoincareSvgOptions& o,
                                 const PoincareSvgStats& stats) {
  std::vector<std::string> lines;
  lines.push_back(o.title.empty() ? "uniformization" : o.title);
  char buffer[400];
  std::snprintf(buffer, sizeof buffer, "%s metric, genus %d%s, max |K| %.1e",
                ricci::to_string(u.geometry).c_str(), u.genus,
                u.doubled ? " (double cover of the open surface)" : "", u.flow.max_error);
  lines.push_back(buffer);
  if (u.geometry == ricci::Geometry::spherical) {
    lines.push_back("conformal embedding on the unit sphere, seen from +z (front faces)");
    return lines;
  }
  std::snprintf(buffer, sizeof buffer,
                "%s: tree-cotree fundamental domain (thick outline, triangles) and %d images under "
                "products of <= %d side pairings",
                u.geometry == ricci::Geometry::hyperbolic ? "Poincare disk" : "plane",
                stats.copies_drawn - 1, o.depth);
  lines.push_back(buffer);
  lines.push_back("sides coloured by the loop whose cotree edge they hold (grey: tree arcs); fill by "
                  "word length; grey background: longer words, not drawn");
  std::snprintf(buffer, sizeof buffer,
                "%d candidate copies under %.1f px skipped; relation residual %.1e; side spread %.1e",
                stats.copies_culled, o.min_copy_px, u.group.relation_residual,
                u.pairings.max_spread);
  lines.push_back(buffer);
  return lines;
}

}  // namespace

std::string uniformization_svg(const ricci::Uniformization& u, const PoincareSvgOptions& o,
                               PoincareSvgStats* stats_out) {
  if (!u.converged()) throw ricci::InvalidInputError("uniformization_svg: the flow did not converge");
  PoincareSvgStats stats;
  Eigen::AlignedBox2d view(Eigen::Vector2d(-1.03, -1.03), Eigen::Vector2d(1.03, 1.03));
  if (u.geometry == ricci::Geometry::euclidean) {
    const double r = 2.2 * u.positions.cwiseAbs().maxCoeff();
    view = Eigen::AlignedBox2d(Eigen::Vector2d(-r, -r), Eigen::Vector2d(r, r));
  }
  SvgCanvas canvas(view, o.width_px);
  if (u.geometry == ricci::Geometry::spherical) {
    draw_sphere(canvas, u);
  } else {
    if (u.geometry == ricci::Geometry::hyperbolic) {
      canvas.add("<circle cx=\"" + svg_number(canvas.px({0, 0}).x()) + "\" cy=\"" +
                 svg_number(canvas.px({0, 0}).y()) + "\" r=\"" +
                 svg_number(canvas.pixels_per_unit()) + "\" fill=\"#d9d9d9\" stroke=\"#000\" stroke-width=\"1.5\"/>");
    }
    draw_cover(canvas, u, o, stats);
  }
  const std::vector<std::string> lines = caption(u, o, stats);
  if (stats_out) *stats_out = stats;
  return captioned_svg(canvas, lines, 12);
}

}  // namespace msp

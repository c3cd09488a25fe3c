#include "msp/svg_cover.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <ricci/mesh/errors.h>

namespace msp {
namespace {

double polygon_area(const Eigen::MatrixX2d& p) {
  double twice = 0.0;
  for (Eigen::Index i = 0; i < p.rows(); ++i) {
    const Eigen::Index j = (i + 1) % p.rows();
    twice += p(i, 0) * p(j, 1) - p(j, 0) * p(i, 1);
  }
  return 0.5 * twice;
}

bool same_motion(const ricci::RigidMotion2& a, const ricci::RigidMotion2& b, double distance) {
  return std::abs(std::remainder(a.angle - b.angle, 2.0 * M_PI)) < 1e-9 &&
         (a.translation - b.translation).norm() < distance;
}

}  // namespace

std::array<int, 3> loop_colour_rgb(int loop) {
  // Distinct on white and for most colour-blind readers (Sasha Trubetskoy's list).
  static const std::array<int, 3> palette[] = {{230, 25, 75},  {60, 180, 75},  {67, 99, 216},
                                               {245, 130, 49}, {145, 30, 180}, {15, 163, 177},
                                               {240, 50, 230}, {154, 99, 36},  {70, 153, 144},
                                               {128, 128, 0},  {0, 0, 117},    {143, 188, 26}};
  if (loop < 0) return {102, 102, 102};
  return palette[static_cast<size_t>(loop) % (sizeof palette / sizeof palette[0])];
}

std::string loop_colour_hex(int loop) {
  const auto c = loop_colour_rgb(loop);
  char buffer[8];
  std::snprintf(buffer, sizeof buffer, "#%02x%02x%02x", c[0], c[1], c[2]);
  return buffer;
}

DomainOutline domain_outline(const ricci::AffineAtlas& atlas) {
  const ricci::Mesh& sliced = atlas.sliced.mesh;
  ricci::HalfedgeHandle start;
  for (auto h : sliced.halfedges()) {
    if (sliced.is_boundary(h)) {
      start = h;
      break;
    }
  }
  if (!start.is_valid())
    throw ricci::TopologyError("atlas picture: the sliced mesh has no boundary");
  DomainOutline outline;
  ricci::HalfedgeHandle h = start;
  do {
    outline.vertices.push_back(sliced.from_vertex_handle(h).idx());
    h = sliced.next_halfedge_handle(h);
  } while (h != start && outline.vertices.size() <= sliced.n_halfedges());
  outline.points.resize(static_cast<Eigen::Index>(outline.vertices.size()), 2);
  for (size_t i = 0; i < outline.vertices.size(); ++i) {
    outline.points.row(static_cast<Eigen::Index>(i)) =
        atlas.layout.positions.row(outline.vertices[i]);
  }
  outline.signed_area = polygon_area(outline.points);
  // Face-less halfedges run clockwise around a counter-clockwise disk.
  if (outline.signed_area < 0) {
    std::reverse(outline.vertices.begin(), outline.vertices.end());
    outline.points = outline.points.colwise().reverse().eval();
    outline.signed_area = -outline.signed_area;
  }
  return outline;
}

std::vector<CutSide> cut_sides(const ricci::Mesh& mesh, const ricci::AffineAtlas& atlas) {
  const auto& corner = atlas.sliced.corner_vertex;
  const Eigen::MatrixX2d& x = atlas.layout.positions;
  std::vector<CutSide> sides;
  for (size_t s = 0; s < atlas.side_pairings.size(); ++s) {
    const auto& arc = atlas.side_pairings[s].halfedges;
    const auto n = static_cast<Eigen::Index>(arc.size());
    CutSide left{static_cast<int>(s), true, Eigen::MatrixX2d(n + 1, 2)};
    CutSide right{static_cast<int>(s), false, Eigen::MatrixX2d(n + 1, 2)};
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto h = arc[static_cast<size_t>(i)];
      const auto o = mesh.opposite_halfedge_handle(h);
      // Copies of from(h) and to(h) inside face(h) (left) and inside face(o) (right).
      left.points.row(i) = x.row(corner[static_cast<size_t>(mesh.prev_halfedge_handle(h).idx())]);
      left.points.row(i + 1) = x.row(corner[static_cast<size_t>(h.idx())]);
      right.points.row(i) = x.row(corner[static_cast<size_t>(o.idx())]);
      right.points.row(i + 1) =
          x.row(corner[static_cast<size_t>(mesh.prev_halfedge_handle(o).idx())]);
    }
    sides.push_back(std::move(left));
    sides.push_back(std::move(right));
  }
  return sides;
}

std::vector<std::string> loop_names(const ricci::AffineAtlas& atlas) {
  const size_t loops = atlas.cut.loops.size();
  std::vector<std::string> names(loops);
  const auto& order = atlas.polygon.canonical_order;
  if (atlas.polygon.canonical && order.size() == loops) {
    for (size_t k = 0; k < order.size(); ++k) {
      names[static_cast<size_t>(order[k])] =
          std::string(k % 2 == 0 ? "a" : "b") + std::to_string(k / 2 + 1);
    }
  } else {
    for (size_t i = 0; i < loops; ++i) names[i] = "c" + std::to_string(i + 1);
  }
  return names;
}

std::vector<ricci::RigidMotion2> cover_motions(const ricci::AffineAtlas& atlas, int depth,
                                               double tolerance) {
  const double distance = tolerance * std::max(atlas.domain_diameter, 1e-300);
  std::vector<ricci::RigidMotion2> generators;
  for (const auto& side : atlas.side_pairings) {
    generators.push_back(side.motion);
    generators.push_back(side.motion.inverse());
  }
  std::vector<ricci::RigidMotion2> found;
  auto known = [&](const ricci::RigidMotion2& m) {
    if (same_motion(m, ricci::RigidMotion2{}, distance)) return true;
    for (const auto& f : found) {
      if (same_motion(m, f, distance)) return true;
    }
    return false;
  };
  std::vector<ricci::RigidMotion2> frontier = {ricci::RigidMotion2{}};
  for (int level = 0; level < depth; ++level) {
    std::vector<ricci::RigidMotion2> next;
    for (const auto& word : frontier) {
      for (const auto& g : generators) {
        const ricci::RigidMotion2 m = word.after(g);
        if (known(m)) continue;
        found.push_back(m);
        next.push_back(m);
      }
    }
    frontier = std::move(next);
  }
  return found;
}

int winding_number(const Eigen::MatrixX2d& polygon, const Eigen::Vector2d& p) {
  // Crossing count with orientation (Sunday's winding number algorithm).
  int winding = 0;
  for (Eigen::Index i = 0; i < polygon.rows(); ++i) {
    const Eigen::Vector2d a = polygon.row(i).transpose();
    const Eigen::Vector2d b = polygon.row((i + 1) % polygon.rows()).transpose();
    const double side = (b.x() - a.x()) * (p.y() - a.y()) - (p.x() - a.x()) * (b.y() - a.y());
    if (a.y() <= p.y()) {
      if (b.y() > p.y() && side > 0) ++winding;
    } else if (b.y() <= p.y() && side < 0) {
      --winding;
    }
  }
  return winding;
}

Eigen::MatrixX2d transformed(const Eigen::MatrixX2d& points, const ricci::RigidMotion2& motion) {
  const Eigen::Matrix2d r = motion.rotation();
  Eigen::MatrixX2d out = points * r.transpose();
  out.rowwise() += motion.translation.transpose();
  return out;
}

}  // namespace msp

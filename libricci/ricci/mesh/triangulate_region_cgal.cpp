// triangulate_region: CGAL's constrained Delaunay triangulation of the polygon's sides and an
// interior lattice, the faces inside found by nesting depth across the constraints.
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <string>
#include <unordered_map>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/triangulate_region.h"

namespace ricci {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<int, Kernel>;
using FaceInfo = CGAL::Triangulation_face_base_with_info_2<int, Kernel>;  // nesting depth
using FaceBase = CGAL::Constrained_triangulation_face_base_2<Kernel, FaceInfo>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Cdt =
    CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::No_constraint_intersection_tag>;
using Point = Kernel::Point_2;

// Nesting depth of every finite face: 0 outside, 1 inside the polygon (odd depth: inside).
void mark_depth(Cdt& cdt) {
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = -1;
  std::deque<std::pair<Cdt::Face_handle, int>> border{{cdt.infinite_face(), 0}};
  while (!border.empty()) {
    const auto [start, depth] = border.front();
    border.pop_front();
    if (start->info() != -1) continue;
    std::deque<Cdt::Face_handle> queue{start};
    while (!queue.empty()) {
      const Cdt::Face_handle f = queue.front();
      queue.pop_front();
      if (f->info() != -1) continue;
      f->info() = depth;
      for (int i = 0; i < 3; ++i) {
        const Cdt::Face_handle n = f->neighbor(i);
        if (n->info() != -1) continue;
        if (cdt.is_constrained(Cdt::Edge(f, i))) {
          border.emplace_back(n, depth + 1);
        } else {
          queue.push_back(n);
        }
      }
    }
  }
}

double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                        const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

// The boundary's sides bucketed in square cells of side `cell`, to find the sides near a point.
class SideGrid {
 public:
  SideGrid(const std::vector<Eigen::Vector2d>& boundary, double cell)
      : boundary_(boundary), cell_(cell) {
    for (std::size_t i = 0; i < boundary.size(); ++i) {
      const Eigen::Vector2d a = boundary[i], b = boundary[(i + 1) % boundary.size()];
      const Eigen::Vector2d lo = a.cwiseMin(b), hi = a.cwiseMax(b);
      for (long x = index(lo.x()); x <= index(hi.x()); ++x) {
        for (long y = index(lo.y()); y <= index(hi.y()); ++y) cells_[key(x, y)].push_back(i);
      }
    }
  }
  // True when a side passes within `cell` of p.
  [[nodiscard]] bool near(const Eigen::Vector2d& p) const {
    for (long x = index(p.x()) - 1; x <= index(p.x()) + 1; ++x) {
      for (long y = index(p.y()) - 1; y <= index(p.y()) + 1; ++y) {
        const auto it = cells_.find(key(x, y));
        if (it == cells_.end()) continue;
        for (std::size_t i : it->second) {
          if (segment_distance(p, boundary_[i], boundary_[(i + 1) % boundary_.size()]) < cell_)
            return true;
        }
      }
    }
    return false;
  }

 private:
  [[nodiscard]] long index(double v) const { return static_cast<long>(std::floor(v / cell_)); }
  [[nodiscard]] static long long key(long x, long y) {
    return (static_cast<long long>(x) << 32) ^ static_cast<long long>(y & 0xffffffffL);
  }
  const std::vector<Eigen::Vector2d>& boundary_;
  double cell_;
  std::unordered_map<long long, std::vector<std::size_t>> cells_;
};

double signed_area(const std::vector<Eigen::Vector2d>& polygon) {
  double sum = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d a = polygon[i], b = polygon[(i + 1) % polygon.size()];
    sum += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * sum;
}

}  // namespace

RegionTriangulation triangulate_region(const std::vector<Eigen::Vector2d>& boundary,
                                       double spacing) {
  const int n = static_cast<int>(boundary.size());
  if (n < 3) {
    throw InvalidInputError("triangulate_region: a polygon needs 3 points, got " +
                            std::to_string(n));
  }
  if (!(spacing > 0.0) || !std::isfinite(spacing)) {
    throw InvalidInputError("triangulate_region: the spacing must be positive and finite");
  }
  if (!(signed_area(boundary) > 0.0)) {
    throw InvalidInputError("triangulate_region: the polygon is not counter-clockwise");
  }
  Cdt cdt;
  std::vector<Cdt::Vertex_handle> handles;
  Eigen::Vector2d lo = boundary[0], hi = boundary[0];
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d& p = boundary[i];
    if (!p.allFinite()) throw InvalidInputError("triangulate_region: a point is not finite");
    const auto v = cdt.insert(Point(p.x(), p.y()));
    if (static_cast<int>(cdt.number_of_vertices()) != i + 1) {
      throw InvalidInputError("triangulate_region: point " + std::to_string(i) +
                              " repeats an earlier one");
    }
    v->info() = i + 1;
    handles.push_back(v);
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  try {
    for (int i = 0; i < n; ++i) cdt.insert_constraint(handles[i], handles[(i + 1) % n]);
  } catch (const std::exception&) {  // CGAL's intersection of constraints
    throw InvalidInputError("triangulate_region: the polygon is not simple");
  }
  if (static_cast<int>(cdt.number_of_vertices()) != n) {
    throw InvalidInputError("triangulate_region: the polygon is not simple");
  }
  mark_depth(cdt);

  const double row = 0.5 * std::sqrt(3.0) * spacing;
  const double columns = std::ceil((hi.x() - lo.x()) / spacing) + 1;
  const double rows = std::ceil((hi.y() - lo.y()) / row) + 1;
  if (columns * rows > 4e6) {
    throw InvalidInputError("triangulate_region: a lattice of " + std::to_string(columns) + " x " +
                            std::to_string(rows) + " points is too large");
  }
  const SideGrid sides(boundary, 0.5 * spacing);
  std::vector<Eigen::Vector2d> interior;
  Cdt::Face_handle hint;
  for (int r = 0; r < static_cast<int>(rows); ++r) {
    for (int c = 0; c < static_cast<int>(columns); ++c) {
      const Eigen::Vector2d p(lo.x() + (c + (r % 2 ? 0.5 : 0.0)) * spacing, lo.y() + r * row);
      hint = cdt.locate(Point(p.x(), p.y()), hint);
      if (cdt.is_infinite(hint) || hint->info() % 2 == 0 || sides.near(p)) continue;
      interior.push_back(p);
    }
  }
  RegionTriangulation out;
  out.positions = boundary;
  for (const auto& p : interior) {
    const auto v = cdt.insert(Point(p.x(), p.y()));
    v->info() = static_cast<int>(out.positions.size()) + 1;
    out.positions.push_back(p);
  }
  mark_depth(cdt);
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (f->info() % 2 == 0) continue;
    out.triangles.emplace_back(f->vertex(0)->info() - 1, f->vertex(1)->info() - 1,
                               f->vertex(2)->info() - 1);
  }
  return out;
}

}  // namespace ricci

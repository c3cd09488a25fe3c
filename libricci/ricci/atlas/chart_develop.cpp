#include "ricci/atlas/chart_develop.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <numeric>
#include <unordered_map>

#include "ricci/layout/layout_e2.h"
#include "ricci/topology/slice.h"

namespace ricci::detail {
namespace {

int find_root(std::vector<int>& parent, int x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

/// Position of halfedge o (of face `f`, as given by face_halfedges) in that face: 0, 1 or 2.
int corner_of(const std::array<HalfedgeHandle, 3>& hs, HalfedgeHandle o) {
  return hs[0] == o ? 0 : (hs[1] == o ? 1 : 2);
}

}  // namespace

std::vector<int> two_ring_faces(const Mesh& mesh, const std::vector<int>& vertices,
                                const std::vector<char>& in_domain) {
  std::vector<int> ring_vertices;
  for (int v : vertices) {
    for (auto f : mesh.vf_range(VertexHandle(v))) {
      if (!in_domain[f.idx()]) continue;
      for (auto w : mesh.fv_range(f)) ring_vertices.push_back(w.idx());
    }
  }
  std::sort(ring_vertices.begin(), ring_vertices.end());
  ring_vertices.erase(std::unique(ring_vertices.begin(), ring_vertices.end()), ring_vertices.end());
  std::vector<int> faces;
  for (int v : ring_vertices) {
    for (auto f : mesh.vf_range(VertexHandle(v))) {
      if (in_domain[f.idx()]) faces.push_back(f.idx());
    }
  }
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  return faces;
}

namespace {

/// Faces placed so far: each with its three vertex copies, copies with positions.
struct Development {
  std::unordered_map<int, int> slot;  // original face -> placement order, -1 = in region only
  std::vector<int> order;             // placed faces in placement order
  std::vector<std::array<int, 3>> corners;
  /// By placed face: the directions of its halfedges (face_halfedges order) in the chart.
  std::vector<std::array<long double, 3>> directions;
  std::vector<Eigen::Vector2d> positions;
  std::vector<int> original;

  int new_vertex(const Eigen::Vector2d& p, int v) {
    positions.push_back(p);
    original.push_back(v);
    return static_cast<int>(positions.size()) - 1;
  }
  /// Placement order of the face across halfedge o (from a placed face), or -1.
  int placed_across(const Mesh& mesh, HalfedgeHandle o) const {
    const auto g = mesh.face_handle(o);
    if (!g.is_valid()) return -1;
    const auto it = slot.find(g.idx());
    return it == slot.end() ? -1 : it->second;
  }
};

constexpr long double kPiL = 3.141592653589793238462643383279502884L;

/// Breadth-first growth from the seed; every face gets fresh copies of the vertex it adds, at
/// its metric distance along the direction develop_directions carries across the faces.
void grow(const Mesh& mesh, const LongLengths& lengths, Development& d) {
  auto length = [&](HalfedgeHandle h) { return lengths[mesh.edge_handle(h).idx()]; };
  for (size_t next = 0; next < d.order.size(); ++next) {
    const auto hs = face_halfedges(mesh, FaceHandle(d.order[next]));
    for (int k = 0; k < 3; ++k) {
      const auto o = mesh.opposite_halfedge_handle(hs[k]);
      const auto g = mesh.face_handle(o);
      if (!g.is_valid()) continue;
      auto it = d.slot.find(g.idx());
      if (it == d.slot.end() || it->second >= 0) continue;
      const auto gs = face_halfedges(mesh, g);
      const int m = corner_of(gs, o);
      std::array<int, 3> c;
      c[m] = d.corners[next][(k + 2) % 3];  // to(o) = from(hs[k])
      c[(m + 2) % 3] = d.corners[next][k];  // from(o) = to(hs[k])
      const long double a_to_b = std::remainder(d.directions[next][k] + kPiL, 2.0L * kPiL);
      const long double l_aw = length(gs[(m + 2) % 3]);
      const DevelopedDirections dir = develop_directions(a_to_b, length(o), l_aw, length(gs[(m + 1) % 3]));
      const Eigen::Vector2d& a = d.positions[c[(m + 2) % 3]];
      const Eigen::Vector2d p(static_cast<double>(a.x() + l_aw * std::cos(dir.a_to_w)),
                              static_cast<double>(a.y() + l_aw * std::sin(dir.a_to_w)));
      c[(m + 1) % 3] = d.new_vertex(p, mesh.to_vertex_handle(gs[(m + 1) % 3]).idx());
      std::array<long double, 3> directions;
      directions[m] = a_to_b;
      directions[(m + 1) % 3] = dir.b_to_w;
      directions[(m + 2) % 3] = std::remainder(dir.a_to_w + kPiL, 2.0L * kPiL);
      it->second = static_cast<int>(d.order.size());
      d.order.push_back(g.idx());
      d.corners.push_back(c);
      d.directions.push_back(directions);
    }
  }
}

/// Union-find parents gluing the copies that meet, within `glue_distance`, across an edge
/// shared by two placed faces.
std::vector<int> glue(const Mesh& mesh, const Development& d, double glue_distance) {
  std::vector<int> parent(d.positions.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (size_t r = 0; r < d.order.size(); ++r) {
    const auto hs = face_halfedges(mesh, FaceHandle(d.order[r]));
    for (int k = 0; k < 3; ++k) {
      const auto o = mesh.opposite_halfedge_handle(hs[k]);
      const int other = d.placed_across(mesh, o);
      if (other < 0) continue;
      const int m = corner_of(face_halfedges(mesh, mesh.face_handle(o)), o);
      const std::array<int, 3>& c = d.corners[other];
      const int pairs[2][2] = {{d.corners[r][(k + 2) % 3], c[m]},
                               {d.corners[r][k], c[(m + 2) % 3]}};
      for (const auto& pr : pairs) {
        const int a = find_root(parent, pr[0]), b = find_root(parent, pr[1]);
        if (a != b && (d.positions[a] - d.positions[b]).norm() <= glue_distance) parent[a] = b;
      }
    }
  }
  return parent;
}

/// The chart of a development: glued copies merged, faces sorted by index.
Chart to_chart(const Development& d, std::vector<int>& parent) {
  Chart chart;
  std::vector<int> compact(d.positions.size(), -1);
  std::vector<Eigen::Vector2d> positions;
  for (size_t v = 0; v < d.positions.size(); ++v) {
    const int root = find_root(parent, static_cast<int>(v));
    if (compact[root] < 0) {
      compact[root] = static_cast<int>(chart.to_original_vertex.size());
      chart.to_original_vertex.push_back(d.original[root]);
      positions.push_back(d.positions[root]);
    }
    compact[v] = compact[root];
  }
  chart.positions.resize(static_cast<Eigen::Index>(positions.size()), 2);
  for (size_t v = 0; v < positions.size(); ++v) {
    chart.positions.row(static_cast<Eigen::Index>(v)) = positions[v].transpose();
  }
  std::vector<size_t> rows(d.order.size());
  std::iota(rows.begin(), rows.end(), 0);
  std::sort(rows.begin(), rows.end(), [&](size_t a, size_t b) { return d.order[a] < d.order[b]; });
  chart.faces.resize(d.order.size());
  chart.corners.resize(static_cast<Eigen::Index>(d.order.size()), 3);
  for (size_t i = 0; i < rows.size(); ++i) {
    chart.faces[i] = d.order[rows[i]];
    for (int k = 0; k < 3; ++k) {
      chart.corners(static_cast<Eigen::Index>(i), k) = compact[d.corners[rows[i]][k]];
    }
  }
  return chart;
}

}  // namespace

Chart develop_chart(const Mesh& mesh, const LongLengths& lengths,
                    const std::vector<int>& region, int seed_face,
                    const Eigen::Matrix<double, 3, 2>& seed_positions, double glue_distance) {
  Development d;
  d.slot.reserve(region.size() * 2);
  for (int f : region) d.slot[f] = -1;
  const auto seed_hs = face_halfedges(mesh, FaceHandle(seed_face));
  std::array<int, 3> seed_corners;
  for (int k = 0; k < 3; ++k) {
    seed_corners[k] =
        d.new_vertex(seed_positions.row(k).transpose(), mesh.to_vertex_handle(seed_hs[k]).idx());
  }
  d.slot[seed_face] = 0;
  d.order.push_back(seed_face);
  d.corners.push_back(seed_corners);
  std::array<long double, 3> seed_directions;  // halfedge k runs from corner k + 2 to corner k
  for (int k = 0; k < 3; ++k) {
    const Eigen::RowVector2d e = seed_positions.row(k) - seed_positions.row((k + 2) % 3);
    seed_directions[k] = std::atan2(static_cast<long double>(e.y()), static_cast<long double>(e.x()));
  }
  d.directions.push_back(seed_directions);
  grow(mesh, lengths, d);
  std::vector<int> parent = glue(mesh, d, glue_distance);
  return to_chart(d, parent);
}

bool places_faithfully(const Mesh& mesh, const Eigen::VectorXd& lengths, const Chart& chart,
                       int row, int face) {
  constexpr double kFaithfulLength = 1e-9;
  const auto hs = face_halfedges(mesh, FaceHandle(face));
  Eigen::Matrix<double, 3, 2> p;
  for (int k = 0; k < 3; ++k) p.row(k) = chart.positions.row(chart.corners(row, k));
  // Halfedge k runs from corner k + 2 to corner k.
  for (int k = 0; k < 3; ++k) {
    const double l = lengths[mesh.edge_handle(hs[k]).idx()];
    const double d = (p.row(k) - p.row((k + 2) % 3)).norm();
    if (!(std::abs(d - l) <= kFaithfulLength * l)) return false;
  }
  const Eigen::Vector2d u = (p.row(1) - p.row(0)).transpose();
  const Eigen::Vector2d v = (p.row(2) - p.row(0)).transpose();
  return u.x() * v.y() - u.y() * v.x() > 0.0;
}

std::vector<int> face_neighbourhood(const Mesh& mesh, int face,
                                    const std::vector<char>& in_domain) {
  std::vector<int> faces;
  for (auto v : mesh.fv_range(FaceHandle(face))) {
    for (auto f : mesh.vf_range(v)) {
      if (in_domain[f.idx()]) faces.push_back(f.idx());
    }
  }
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  return faces;
}

bool holds_as_one_piece(const Mesh& mesh, const Chart& chart,
                        const std::vector<int>& neighbourhood) {
  std::vector<std::pair<int, int>> copies;  // (original vertex, chart vertex)
  for (int f : neighbourhood) {
    const int row = chart.slot(f);
    if (row < 0) return false;
    const auto hs = face_halfedges(mesh, FaceHandle(f));
    for (int k = 0; k < 3; ++k) {
      copies.push_back({mesh.to_vertex_handle(hs[k]).idx(), chart.corners(row, k)});
    }
  }
  std::sort(copies.begin(), copies.end());
  for (size_t i = 1; i < copies.size(); ++i) {
    if (copies[i].first == copies[i - 1].first && copies[i].second != copies[i - 1].second) {
      return false;
    }
  }
  return true;
}

}  // namespace ricci::detail

#include "ricci/atlas/chart_develop.h"

#include <algorithm>
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

Chart develop_chart(const Mesh& mesh, const Eigen::VectorXd& lengths,
                    const std::vector<int>& region, int seed_face,
                    const Eigen::Matrix<double, 3, 2>& seed_positions, double glue_distance) {
  std::unordered_map<int, int> slot;  // original face -> placement order, -1 = in region only
  slot.reserve(region.size() * 2);
  for (int f : region) slot[f] = -1;
  std::vector<int> order;
  std::vector<std::array<int, 3>> corners;
  std::vector<Eigen::Vector2d> positions;
  std::vector<int> original;
  auto new_vertex = [&](const Eigen::Vector2d& p, int v) {
    positions.push_back(p);
    original.push_back(v);
    return static_cast<int>(positions.size()) - 1;
  };
  auto length = [&](HalfedgeHandle h) { return lengths[mesh.edge_handle(h).idx()]; };

  const auto seed_hs = face_halfedges(mesh, FaceHandle(seed_face));
  std::array<int, 3> seed_corners;
  for (int k = 0; k < 3; ++k) {
    seed_corners[k] =
        new_vertex(seed_positions.row(k).transpose(), mesh.to_vertex_handle(seed_hs[k]).idx());
  }
  slot[seed_face] = 0;
  order.push_back(seed_face);
  corners.push_back(seed_corners);
  for (size_t next = 0; next < order.size(); ++next) {
    const int f = order[next];
    const auto hs = face_halfedges(mesh, FaceHandle(f));
    for (int k = 0; k < 3; ++k) {
      const auto o = mesh.opposite_halfedge_handle(hs[k]);
      const auto g = mesh.face_handle(o);
      if (!g.is_valid()) continue;
      auto it = slot.find(g.idx());
      if (it == slot.end() || it->second >= 0) continue;
      const auto gs = face_halfedges(mesh, g);
      const int m = corner_of(gs, o);
      std::array<int, 3> c;
      c[m] = corners[next][(k + 2) % 3];  // to(o) = from(hs[k])
      c[(m + 2) % 3] = corners[next][k];  // from(o) = to(hs[k])
      const Eigen::Vector2d p = place_third_vertex(positions[c[(m + 2) % 3]], positions[c[m]],
                                                   length(mesh.prev_halfedge_handle(o)),
                                                   length(mesh.next_halfedge_handle(o)));
      c[(m + 1) % 3] = new_vertex(p, mesh.to_vertex_handle(gs[(m + 1) % 3]).idx());
      it->second = static_cast<int>(order.size());
      order.push_back(g.idx());
      corners.push_back(c);
    }
  }

  // Glue copies that meet across an edge shared by two placed faces.
  std::vector<int> parent(positions.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (size_t r = 0; r < order.size(); ++r) {
    const auto hs = face_halfedges(mesh, FaceHandle(order[r]));
    for (int k = 0; k < 3; ++k) {
      const auto o = mesh.opposite_halfedge_handle(hs[k]);
      const auto g = mesh.face_handle(o);
      if (!g.is_valid()) continue;
      const auto it = slot.find(g.idx());
      if (it == slot.end() || it->second < 0) continue;
      const int m = corner_of(face_halfedges(mesh, g), o);
      const std::array<int, 3>& c = corners[it->second];
      const int pairs[2][2] = {{corners[r][(k + 2) % 3], c[m]}, {corners[r][k], c[(m + 2) % 3]}};
      for (const auto& pr : pairs) {
        const int a = find_root(parent, pr[0]), b = find_root(parent, pr[1]);
        if (a != b && (positions[a] - positions[b]).norm() <= glue_distance) parent[a] = b;
      }
    }
  }

  Chart chart;
  std::vector<int> compact(positions.size(), -1);
  for (size_t v = 0; v < positions.size(); ++v) {
    const int root = find_root(parent, static_cast<int>(v));
    if (compact[root] < 0) {
      compact[root] = static_cast<int>(chart.to_original_vertex.size());
      chart.to_original_vertex.push_back(original[root]);
    }
  }
  chart.positions.resize(static_cast<Eigen::Index>(chart.to_original_vertex.size()), 2);
  for (size_t v = 0; v < positions.size(); ++v) {
    if (find_root(parent, static_cast<int>(v)) == static_cast<int>(v)) {
      chart.positions.row(compact[v]) = positions[v].transpose();
    }
  }
  std::vector<size_t> rows(order.size());
  std::iota(rows.begin(), rows.end(), 0);
  std::sort(rows.begin(), rows.end(), [&](size_t a, size_t b) { return order[a] < order[b]; });
  chart.faces.resize(order.size());
  chart.corners.resize(static_cast<Eigen::Index>(order.size()), 3);
  for (size_t i = 0; i < rows.size(); ++i) {
    chart.faces[i] = order[rows[i]];
    for (int k = 0; k < 3; ++k) {
      chart.corners(static_cast<Eigen::Index>(i), k) =
          compact[find_root(parent, corners[rows[i]][k])];
    }
  }
  return chart;
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

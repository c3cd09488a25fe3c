#include "ricci/mesh/boundary_band.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "ricci/mesh/arrays.h"
#include "ricci/mesh/boundary_loops.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/soup_distance.h"

namespace ricci {
namespace {

using Loop = std::vector<int>;  // vertex indices along the face-less halfedges

std::vector<Loop> vertex_loops(const Mesh& mesh) {
  std::vector<Loop> loops;
  for (const auto& halfedges : find_boundary_loops(mesh)) {
    loops.emplace_back();
    for (auto h : halfedges) loops.back().push_back(mesh.from_vertex_handle(h).idx());
  }
  return loops;
}

std::vector<std::array<int, 2>> loop_segments(const Loop& loop) {
  std::vector<std::array<int, 2>> s;
  for (std::size_t i = 0; i < loop.size(); ++i) s.push_back({loop[i], loop[(i + 1) % loop.size()]});
  return s;
}

// Vertices and edge midpoints of a closed polyline.
Eigen::MatrixX3d loop_samples(const Eigen::MatrixX3d& x, const Loop& loop) {
  Eigen::MatrixX3d out(static_cast<Eigen::Index>(2 * loop.size()), 3);
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const auto r = static_cast<Eigen::Index>(2 * i);
    out.row(r) = x.row(loop[i]);
    out.row(r + 1) = 0.5 * (x.row(loop[i]) + x.row(loop[(i + 1) % loop.size()]));
  }
  return out;
}

// Hausdorff distance between two closed polylines, sampled at vertices and edge midpoints.
double loop_distance(const Eigen::MatrixX3d& xa, const Loop& a, const Eigen::MatrixX3d& xb,
                     const Loop& b) {
  const SegmentSoupDistance ta(xa, loop_segments(a)), tb(xb, loop_segments(b));
  return std::max(tb.distances(loop_samples(xa, a)).maxCoeff(),
                  ta.distances(loop_samples(xb, b)).maxCoeff());
}

double segment_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                        const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = b - a;
  const double l2 = d.squaredNorm();
  const double t = l2 > 0.0 ? std::clamp((p - a).dot(d) / l2, 0.0, 1.0) : 0.0;
  return (p - a - t * d).norm();
}

// Positions (into `loop`) kept by a Douglas-Peucker thinning of the closed polyline to `tol`,
// in loop order; the first vertex and the one farthest from it are always kept.
std::vector<int> thinned(const Eigen::MatrixX3d& x, const Loop& loop, double tol) {
  const int n = static_cast<int>(loop.size());
  const auto at = [&](int i) -> Eigen::Vector3d { return x.row(loop[i % n]).transpose(); };
  int far = 0;
  for (int i = 1; i < n; ++i)
    if ((at(i) - at(0)).norm() > (at(far) - at(0)).norm()) far = i;
  std::vector<char> keep(static_cast<std::size_t>(n), 0);
  keep[0] = keep[static_cast<std::size_t>(far)] = 1;
  std::vector<std::array<int, 2>> stack{{0, far}, {far, n}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    int worst = -1;
    double worst_distance = tol;
    for (int k = i + 1; k < j; ++k) {
      const double d = segment_distance(at(k), at(i), at(j));
      if (d > worst_distance) {
        worst = k;
        worst_distance = d;
      }
    }
    if (worst < 0) continue;
    keep[static_cast<std::size_t>(worst)] = 1;
    stack.push_back({i, worst});
    stack.push_back({worst, j});
  }
  std::vector<int> kept;
  for (int i = 0; i < n; ++i)
    if (keep[static_cast<std::size_t>(i)]) kept.push_back(i);
  return kept;
}

// Area-weighted unit normal of `mesh` at vertex v.
Eigen::Vector3d vertex_normal(const Mesh& mesh, VertexHandle v) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (auto f : mesh.vf_range(v)) {
    std::array<Eigen::Vector3d, 3> p;
    int k = 0;
    for (auto u : mesh.fv_range(f)) p[static_cast<std::size_t>(k++)] = to_eigen(mesh.point(u));
    n += (p[1] - p[0]).cross(p[2] - p[0]);
  }
  return n.norm() > 0.0 ? Eigen::Vector3d(n.normalized()) : n;
}

// The coarse mesh as a face list while its bands are rebuilt (vertex indices stay; new vertices
// are appended, removed ones left unreferenced).
struct FaceList {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3>> faces;
};

long long key(int a, int b) { return (static_cast<long long>(a) << 32) | static_cast<unsigned>(b); }

// The face-less halfedges (from -> to) of a face list.
std::unordered_map<int, int> boundary_next(const FaceList& list) {
  std::unordered_set<long long> used;
  for (const auto& f : list.faces)
    for (int j = 0; j < 3; ++j) used.insert(key(f[j], f[(j + 1) % 3]));
  std::unordered_map<int, int> next;
  for (const auto& f : list.faces)
    for (int j = 0; j < 3; ++j) {
      const int a = f[j], b = f[(j + 1) % 3];
      if (used.count(key(b, a))) continue;
      if (!next.emplace(b, a).second) next[b] = -1;  // two face-less halfedges leave b: a pinch
    }
  return next;
}

// The one loop of face-less halfedges of `after` that `before` did not have, in order, or an
// empty loop when they are not exactly one simple loop apart from `before`'s boundary.
Loop new_inner_loop(const std::unordered_map<int, int>& before,
                    const std::unordered_map<int, int>& after) {
  std::unordered_map<int, int> fresh;
  for (const auto& [a, b] : after) {
    const auto old = before.find(a);
    if (old != before.end() && old->second == b) continue;
    if (b < 0 || before.count(a)) return {};  // a pinch, or the new boundary touches an old one
    fresh.emplace(a, b);
  }
  if (fresh.empty()) return {};
  Loop loop{fresh.begin()->first};
  while (loop.size() <= fresh.size()) {
    const auto next = fresh.find(loop.back());
    if (next == fresh.end()) return {};
    if (next->second == loop.front()) break;
    loop.push_back(next->second);
  }
  return loop.size() == fresh.size() ? loop : Loop{};
}

struct StripCorner {
  Eigen::Vector3d point;
  Eigen::Vector3d normal;  // the dense surface's (zero on the inner ring)
};

// Whether triangle (a, b, c) faces like `reference` (within ~78 degrees) and is no flatter
// than min_shape.
bool acceptable(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                const Eigen::Vector3d& reference, double min_shape) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double longest =
      std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  return n.norm() >= min_shape * longest && n.dot(reference) > 0.2 * n.norm();
}

// The strip between the closed loops `inner` (ring vertex indices, along its face-less
// halfedges) and `outer` (new vertex indices, along the dense loop's face-less halfedges):
// triangles (b_i, b_i+1, e_k) and (b_i, e_k+1, e_k), each edge of both loops used once, by
// dynamic programming over (i, k) for the least total rung length. Empty when none is acceptable.
std::vector<std::array<int, 3>> stitch(const FaceList& list, const Loop& inner,
                                       const std::vector<int>& outer,
                                       const std::vector<Eigen::Vector3d>& outer_normals,
                                       double min_shape) {
  const int m = static_cast<int>(inner.size()), n = static_cast<int>(outer.size());
  const auto b = [&](int i) -> const Eigen::Vector3d& { return list.points[inner[i % m]]; };
  int k0 = 0;
  for (int k = 1; k < n; ++k)
    if ((list.points[outer[k]] - b(0)).norm() < (list.points[outer[k0]] - b(0)).norm()) k0 = k;
  const auto e = [&](int k) { return (k0 + k) % n; };
  const auto ep = [&](int k) -> const Eigen::Vector3d& { return list.points[outer[e(k)]]; };
  const double inf = std::numeric_limits<double>::infinity();
  const auto index = [&](int i, int k) { return static_cast<std::size_t>(i * (n + 1) + k); };
  std::vector<double> cost(static_cast<std::size_t>((m + 1) * (n + 1)), inf);
  std::vector<char> from_inner(cost.size(), 0);
  cost[0] = 0.0;
  for (int i = 0; i <= m; ++i) {
    for (int k = 0; k <= n; ++k) {
      const double c = cost[index(i, k)];
      if (!(c < inf)) continue;
      if (i < m && acceptable(b(i), b(i + 1), ep(k), outer_normals[e(k)], min_shape)) {
        const double next = c + (b(i + 1) - ep(k)).norm();
        if (next < cost[index(i + 1, k)]) {
          cost[index(i + 1, k)] = next;
          from_inner[index(i + 1, k)] = 1;
        }
      }
      const Eigen::Vector3d normal = outer_normals[e(k)] + outer_normals[e(k + 1)];
      if (k < n && acceptable(b(i), ep(k + 1), ep(k), normal, min_shape)) {
        const double next = c + (b(i) - ep(k + 1)).norm();
        if (next < cost[index(i, k + 1)]) {
          cost[index(i, k + 1)] = next;
          from_inner[index(i, k + 1)] = 0;
        }
      }
    }
  }
  std::vector<std::array<int, 3>> strip;
  if (!(cost[index(m, n)] < inf)) return strip;
  for (int i = m, k = n; i > 0 || k > 0;) {
    if (from_inner[index(i, k)]) {
      --i;
      strip.push_back({inner[i % m], inner[(i + 1) % m], outer[e(k)]});
    } else {
      --k;
      strip.push_back({inner[i % m], outer[e(k + 1)], outer[e(k)]});
    }
  }
  return strip;
}

// The dense loop (thinned) appended to list.points; returns the new indices in loop order and
// the dense surface's normal at each.
std::vector<int> append_outer(const Mesh& dense, const Eigen::MatrixX3d& x, const Loop& loop,
                              double tol, FaceList& list, std::vector<Eigen::Vector3d>& normals) {
  std::vector<int> outer;
  for (int i : thinned(x, loop, tol)) {
    const int v = loop[static_cast<std::size_t>(i)];
    outer.push_back(static_cast<int>(list.points.size()));
    list.points.emplace_back(x.row(v).transpose());
    normals.push_back(vertex_normal(dense, dense.vertex_handle(v)));
  }
  return outer;
}

// Rebuilds the band of `loop` (coarse vertex indices) in `list` towards dense loop `target`;
// false (list unchanged) when it cannot.
bool rebuild_band(FaceList& list, const Loop& loop, const Mesh& dense,
                  const Eigen::MatrixX3d& dense_x, const Loop& target,
                  const BoundaryBandOptions& options, double diagonal, BoundaryBandResult& result) {
  std::unordered_set<int> on_loop(loop.begin(), loop.end());
  FaceList kept{list.points, {}};
  for (const auto& f : list.faces)
    if (!on_loop.count(f[0]) && !on_loop.count(f[1]) && !on_loop.count(f[2]))
      kept.faces.push_back(f);
  const Loop inner = new_inner_loop(boundary_next(list), boundary_next(kept));
  if (inner.size() < 3) return false;
  std::vector<Eigen::Vector3d> normals;
  const std::vector<int> outer =
      append_outer(dense, dense_x, target, options.tolerance * diagonal, kept, normals);
  const auto strip = stitch(kept, inner, outer, normals, options.min_shape);
  if (strip.empty()) return false;
  result.faces_removed += static_cast<int>(list.faces.size() - kept.faces.size());
  result.faces_added += static_cast<int>(strip.size());
  kept.faces.insert(kept.faces.end(), strip.begin(), strip.end());
  list = std::move(kept);
  return true;
}

// The face list as a mesh (unreferenced vertices dropped); false when a face cannot be added
// (not a manifold).
bool to_mesh(const FaceList& list, Mesh& out) {
  std::vector<int> index(list.points.size(), -1);
  Mesh mesh;
  for (const auto& f : list.faces)
    for (int v : f)
      if (index[static_cast<std::size_t>(v)] < 0) {
        index[static_cast<std::size_t>(v)] = static_cast<int>(mesh.n_vertices());
        mesh.add_vertex(to_openmesh(list.points[static_cast<std::size_t>(v)]));
      }
  for (const auto& f : list.faces) {
    const auto h = [&](int k) { return mesh.vertex_handle(index[static_cast<std::size_t>(f[k])]); };
    if (!mesh.add_face(h(0), h(1), h(2)).is_valid()) return false;
  }
  out = std::move(mesh);
  return true;
}

// The dense loop that most of `loop`'s vertices are nearest to.
int followed_loop(const Eigen::MatrixX3d& x, const Loop& loop, const SegmentSoupDistance& tree,
                  const std::vector<int>& segment_loop, int loop_count) {
  std::vector<int> votes(static_cast<std::size_t>(loop_count), 0);
  for (int v : loop)
    ++votes[static_cast<std::size_t>(
        segment_loop[static_cast<std::size_t>(tree.closest(x.row(v).transpose()).primitive)])];
  return static_cast<int>(std::max_element(votes.begin(), votes.end()) - votes.begin());
}

}  // namespace

BoundaryBandResult rebuild_boundary_bands(Mesh& coarse, const Mesh& dense,
                                          const BoundaryBandOptions& options) {
  if (!(options.tolerance > 0.0) || !(options.min_shape >= 0.0 && options.min_shape < 1.0))
    throw InvalidInputError("rebuild_boundary_bands: need tolerance > 0, min_shape in [0, 1)");
  BoundaryBandResult result;
  const std::vector<Loop> targets = vertex_loops(dense);
  const std::vector<Loop> loops = vertex_loops(coarse);
  if (!(options.rebuild_above > 0.0) || targets.empty() || loops.empty()) return result;
  const Eigen::MatrixX3d dense_x = vertex_positions(dense), x = vertex_positions(coarse);
  const double diagonal = (dense_x.colwise().maxCoeff() - dense_x.colwise().minCoeff()).norm();
  std::vector<std::array<int, 2>> segments;
  std::vector<int> segment_loop;
  for (std::size_t t = 0; t < targets.size(); ++t)
    for (const auto& s : loop_segments(targets[t])) {
      segments.push_back(s);
      segment_loop.push_back(static_cast<int>(t));
    }
  const SegmentSoupDistance tree(dense_x, segments);
  FaceList list;
  for (auto v : coarse.vertices()) list.points.push_back(to_eigen(coarse.point(v)));
  for (auto f : coarse.faces()) {
    std::array<int, 3> face{};
    int k = 0;
    for (auto v : coarse.fv_range(f)) face[static_cast<std::size_t>(k++)] = v.idx();
    list.faces.push_back(face);
  }
  for (const Loop& loop : loops) {
    const Loop& target = targets[static_cast<std::size_t>(
        followed_loop(x, loop, tree, segment_loop, static_cast<int>(targets.size())))];
    const double before = loop_distance(x, loop, dense_x, target);
    if (before <= options.rebuild_above * diagonal) continue;
    FaceList attempt = list;
    if (!rebuild_band(attempt, loop, dense, dense_x, target, options, diagonal, result)) continue;
    list = std::move(attempt);
    ++result.loops_rebuilt;
  }
  Mesh rebuilt;
  if (result.loops_rebuilt == 0 || !to_mesh(list, rebuilt) ||
      euler_characteristic(rebuilt) != euler_characteristic(coarse) ||
      find_boundary_loops(rebuilt).size() != loops.size())
    return BoundaryBandResult{};
  coarse = std::move(rebuilt);
  return result;
}

}  // namespace ricci

// The annulus map of a doubly connected domain (Algorithm 4): flat metric with geodesic
// boundaries, slice along the shortest path between them, layout, exponential map.
#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include "ricci/analysis/module_internal.h"
#include "ricci/layout/layout_e2.h"
#include "ricci/mesh/errors.h"
#include "ricci/topology/slice.h"

namespace ricci::detail {

namespace {

/// The period of the strip: the left copy of a path vertex minus its right copy (the same for
/// every copy because the flat cylinder's holonomy is a translation: each boundary's total
/// geodesic curvature is 0).
Complex strip_period(const Mesh& mesh, const std::vector<HalfedgeHandle>& path,
                     const SlicedMesh& sliced, const LayoutE2Result& layout) {
  const auto at = [&](HalfedgeHandle h) {
    const int v = sliced.mesh.from_vertex_handle(h).idx();
    return Complex(layout.positions(v, 0), layout.positions(v, 1));
  };
  Complex period = 0;
  int count = 0;
  for (HalfedgeHandle h : path) {
    const int k = mesh.halfedge_handle(mesh.edge_handle(h), 0) == h ? 0 : 1;
    const CutEdgeSides& sides = *std::find_if(
        sliced.cut_sides.begin(), sliced.cut_sides.end(),
        [&](const CutEdgeSides& s) { return s.edge == mesh.edge_handle(h); });
    // side[k] runs along h on its left; side[1-k] runs against it on the right.
    const HalfedgeHandle left = sides.side[k], right = sides.side[1 - k];
    period += at(left) - at(sliced.mesh.next_halfedge_handle(right));
    period += at(sliced.mesh.next_halfedge_handle(left)) - at(right);
    count += 2;
  }
  return period / static_cast<double>(count);
}

}  // namespace

AnnulusMap annulus_map(const Mesh& mesh, const MeshTables& tables, const FlowOptions& options,
                       int outer_vertex) {
  AnnulusMap map;
  Targets targets;
  targets.curvature = Eigen::VectorXd::Zero(tables.num_vertices());
  map.flow = flow(mesh, targets, options);
  if (!map.flow.converged() && map.flow.status != FlowStatus::stalled) return map;
  std::vector<int> loop_of(tables.num_vertices(), -1);
  for (int k = 0; k < 2; ++k) {
    for (int v : tables.boundary_loops[k]) loop_of[v] = k;
  }
  // The cut: the shortest path from loop 0 to loop 1 through the interior.
  map.path = shortest_path_to_loop(
      mesh, loop_of, map.flow.lengths, tables.boundary_loops[0], [](int loop) { return loop == 1; },
      std::vector<char>(loop_of.size(), 0));
  if (map.path.empty()) {
    throw TopologyError("no path joins the two boundary loops through the interior");
  }
  std::vector<char> is_cut(mesh.n_edges(), 0);
  for (HalfedgeHandle h : map.path) is_cut[mesh.edge_handle(h).idx()] = 1;
  map.sliced = slice_along(mesh, is_cut);
  check_disk(map.sliced, "annulus slice");
  const LayoutE2Result layout =
      layout_e2(map.sliced.mesh, sliced_edge_lengths(map.sliced, map.flow.lengths));
  // w = 2πi p / T sends the period to 2πi: Re w is the log-radius after exp.
  const Complex scale = Complex(0, 2 * M_PI) / strip_period(mesh, map.path, map.sliced, layout);
  const int n = static_cast<int>(map.sliced.mesh.n_vertices());
  map.w.resize(n);
  for (int v = 0; v < n; ++v) {
    map.w[v] = scale * Complex(layout.positions(v, 0), layout.positions(v, 1));
  }
  map.copy_of.assign(tables.num_vertices(), -1);
  for (int v = 0; v < n; ++v) map.copy_of[map.sliced.to_original_vertex[v]] = v;
  double mean[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    for (int v : tables.boundary_loops[k]) mean[k] += map.w[map.copy_of[v]].real();
    mean[k] /= static_cast<double>(tables.boundary_loops[k].size());
  }
  map.module = std::abs(mean[1] - mean[0]) / (2 * M_PI);
  for (int s = 0; s < n; ++s) {
    const int k = loop_of[map.sliced.to_original_vertex[s]];
    if (k >= 0) map.roundness = std::max(map.roundness, std::abs(map.w[s].real() - mean[k]));
  }
  // The outer loop goes to |z| = 1: w -> -w (z -> 1/z) swaps the two when asked.
  int outer = mean[0] >= mean[1] ? 0 : 1;
  double shift = mean[outer];
  if (outer_vertex >= 0 && loop_of[outer_vertex] != outer) {
    map.w = -map.w;
    outer = 1 - outer;
    shift = -mean[outer];
  }
  map.w.array() -= Complex(shift, 0);
  map.z.resize(tables.num_vertices());
  for (int v = 0; v < tables.num_vertices(); ++v) map.z[v] = std::exp(map.w[map.copy_of[v]]);
  return map;
}

void annulus_module(const Mesh& mesh, const MeshTables& tables, const ModuleOptions& options,
                    ModuleResult& result) {
  const AnnulusMap map = annulus_map(mesh, tables, options.flow, -1);
  record_flow(map.flow, options, result);
  if (map.w.size() == 0) return;
  result.values = {map.module};
  result.names = {"module"};
  result.roundness = map.roundness;
  result.corners = {mesh.from_vertex_handle(map.path.front()).idx(),
                    mesh.to_vertex_handle(map.path.back()).idx()};
  CanonicalDomain& domain = result.domain;
  const Eigen::Index n = map.w.size();
  domain.positions.resize(n, 2);
  for (Eigen::Index v = 0; v < n; ++v) {
    const Complex z = std::exp(map.w[v]);
    domain.positions.row(v) << z.real(), z.imag();
  }
  copy_faces(map.sliced.mesh, domain);
  for (const auto& loop : tables.boundary_loops) {
    std::vector<int> polyline;
    for (int v : loop) polyline.push_back(map.copy_of[v]);
    domain.boundary_loop.push_back(static_cast<int>(domain.boundaries.size()));
    domain.boundaries.push_back(polyline);
  }
}

std::vector<HalfedgeHandle> shortest_path_to_loop(const Mesh& mesh, const std::vector<int>& loop_of,
                                                  const EdgeLengths& lengths,
                                                  const std::vector<int>& sources,
                                                  const std::function<bool(int)>& is_target,
                                                  const std::vector<char>& used) {
  const int n = static_cast<int>(loop_of.size());
  std::vector<double> dist(n, std::numeric_limits<double>::infinity());
  std::vector<HalfedgeHandle> parent(n);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (int s : sources) {
    dist[s] = 0;
    queue.push({0.0, s});
  }
  int end = -1;
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > dist[v]) continue;
    if (loop_of[v] >= 0 && is_target(loop_of[v])) {
      end = v;
      break;
    }
    for (HalfedgeHandle h : mesh.voh_range(mesh.vertex_handle(v))) {
      const int w = mesh.to_vertex_handle(h).idx();
      if (used[w] || (loop_of[w] >= 0 && !is_target(loop_of[w]))) continue;
      const double nd = d + lengths[mesh.edge_handle(h).idx()];
      if (nd < dist[w]) {
        dist[w] = nd;
        parent[w] = h;
        queue.push({nd, w});
      }
    }
  }
  std::vector<HalfedgeHandle> path;
  for (int v = end; v >= 0 && dist[v] > 0; v = mesh.from_vertex_handle(parent[v]).idx()) {
    path.push_back(parent[v]);
  }
  std::reverse(path.begin(), path.end());
  return path;
}

}  // namespace ricci::detail

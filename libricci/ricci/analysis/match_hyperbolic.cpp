// Deformable surface matching by the hyperbolic method (Algorithm 9): the hyperbolic metric with
// geodesic boundaries, the loops joined by shortest paths into a tree, the cut disk laid out in
// the Poincaré disk and carried to the Klein model, where geodesics are chords and the
// right-angled polygon is convex; A and B mapped harmonically onto B's polygon.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "ricci/analysis/match_internal.h"
#include "ricci/analysis/module_internal.h"
#include "ricci/hyperbolic/klein.h"
#include "ricci/hyperbolic/layout_h2.h"
#include "ricci/mesh/errors.h"
#include "ricci/util/cross2d.h"
#include "ricci/util/stopwatch.h"

namespace ricci::detail {

namespace {

/// The loops joined into a tree by shortest paths.
struct LoopTree {
  std::vector<char> is_cut;               ///< By mesh edge.
  std::vector<int> cut_of_edge;           ///< By mesh edge: the cut through it, else -1.
  std::vector<std::array<int, 2>> joins;  ///< By cut: the loop ranks it joins (reached, new).
  std::vector<int> first_end;             ///< By cut: its end on the loop reached before it.
};

/// Which loops each cut joins, by rank (c0 the longest): {loop reached, new loop}.
using LoopPlan = std::vector<std::array<int, 2>>;

/// The loops joined into a tree by n shortest edge paths under `lengths`, through interior
/// vertices no earlier cut uses and starting at a vertex no cut ends at. With an empty `plan`,
/// Prim's tree from c0 (each cut from the loops joined so far to the nearest other loop);
/// otherwise cut k joins plan[k][0] to plan[k][1], whatever is nearer.
/// \throw TopologyError when a loop cannot be reached.
LoopTree join_loops(const Mesh& mesh, const MeshTables& tables, const Eigen::VectorXd& lengths,
                    const LoopPlan& plan, const char* name) {
  const int n = tables.num_vertices();
  const std::vector<int> order = loops_by_length(mesh, tables);
  const int loops = static_cast<int>(order.size());
  std::vector<int> loop_of(n, -1);
  for (int rank = 0; rank < loops; ++rank) {
    for (int v : tables.boundary_loops[order[rank]]) loop_of[v] = rank;
  }
  LoopTree tree;
  tree.is_cut.assign(mesh.n_edges(), 0);
  tree.cut_of_edge.assign(mesh.n_edges(), -1);
  std::vector<char> joined(loops, 0), used(n, 0);
  joined[0] = 1;
  for (int cut = 0; cut + 1 < loops; ++cut) {
    const bool planned = !plan.empty();
    const auto source = [&](int rank) {
      return planned ? rank == plan[cut][0] : joined[rank] != 0;
    };
    const auto target = [&](int rank) { return planned ? rank == plan[cut][1] : !joined[rank]; };
    std::vector<int> sources;
    for (int v = 0; v < n; ++v) {
      if (loop_of[v] >= 0 && source(loop_of[v]) && !used[v]) sources.push_back(v);
    }
    const std::vector<HalfedgeHandle> path =
        shortest_path_to_loop(mesh, loop_of, lengths, sources, target, used);
    if (path.empty()) {
      throw TopologyError(std::string(name) + ": no path joins the boundary loops reached so " +
                          "far to another one without crossing the earlier cuts");
    }
    const int start = mesh.from_vertex_handle(path.front()).idx();
    const int end = mesh.to_vertex_handle(path.back()).idx();
    used[start] = 1;
    for (HalfedgeHandle h : path) {
      tree.is_cut[mesh.edge_handle(h).idx()] = 1;
      tree.cut_of_edge[mesh.edge_handle(h).idx()] = cut;
      used[mesh.to_vertex_handle(h).idx()] = 1;
    }
    tree.joins.push_back({loop_of[start], loop_of[end]});
    tree.first_end.push_back(start);
    joined[loop_of[end]] = 1;
  }
  return tree;
}

/// A surface cut along its loop tree and laid out in the Klein model.
struct KleinDisk {
  SlicedMesh sliced;
  Eigen::MatrixX2d klein;    ///< By sliced vertex: the layout in the Klein model.
  Eigen::VectorXd chords;    ///< By sliced edge: Euclidean length in the Klein layout.
  std::vector<int> walk;     ///< The disk's boundary, counter-clockwise.
  std::vector<double> arc;   ///< Hyperbolic arc length along the walk (walk.size() + 1).
  std::vector<int> corners;  ///< Walk positions of the cut ends.
  std::vector<int> labels;   ///< By arc: the loop rank (>= 0) or -1 - the cut's index.
  std::vector<std::array<int, 2>> joins;
  std::vector<int> loop_order;  ///< The loop of each boundary side, ccw.
};

/// Step 1 of Algorithm 9: the hyperbolic metric with geodesic boundaries.
FlowResult hyperbolic_metric(const Mesh& mesh, const MeshTables& tables,
                             const MatchOptions& options, const char* name,
                             ParameterDomain& domain) {
  FlowOptions flow_options = options.flow;
  flow_options.geometry = Geometry::hyperbolic;
  Targets targets;
  targets.curvature = Eigen::VectorXd::Zero(tables.num_vertices());  // geodesic boundaries
  FlowResult hyperbolic = flow(mesh, targets, flow_options);
  record_match_flow(hyperbolic, options, name, domain);
  return hyperbolic;
}

/// Steps 2-3 of Algorithm 9 on one surface: the cut, the layout, the polygon's corners.
KleinDisk klein_disk(const Mesh& mesh, const MeshTables& tables, const FlowResult& hyperbolic,
                     const LoopPlan& plan, const char* name) {
  const LoopTree tree = join_loops(mesh, tables, hyperbolic.lengths, plan, name);
  KleinDisk disk;
  disk.joins = tree.joins;
  disk.sliced = slice_along(mesh, tree.is_cut);
  check_disk(disk.sliced, "loop-tree cut");
  const Eigen::VectorXd lengths = sliced_edge_lengths(disk.sliced, hyperbolic.lengths);
  const LayoutH2Result layout = layout_h2(disk.sliced.mesh, lengths);
  const Mesh& cut = disk.sliced.mesh;
  const int n = static_cast<int>(cut.n_vertices());
  disk.klein.resize(n, 2);
  for (int v = 0; v < n; ++v) {
    const Complex k = klein_from_poincare(layout.positions[v]);
    disk.klein.row(v) << k.real(), k.imag();
  }
  disk.chords.resize(static_cast<Eigen::Index>(cut.n_edges()));
  for (EdgeHandle e : cut.edges()) {
    const HalfedgeHandle h = cut.halfedge_handle(e, 0);
    disk.chords[e.idx()] = (disk.klein.row(cut.from_vertex_handle(h).idx()) -
                            disk.klein.row(cut.to_vertex_handle(h).idx()))
                               .norm();
  }
  // Cut ends: the corners. Rank of each loop vertex, for the loop arcs' labels.
  const std::vector<int> order = loops_by_length(mesh, tables);
  std::vector<int> loop_of(tables.num_vertices(), -1);
  for (size_t rank = 0; rank < order.size(); ++rank) {
    for (int v : tables.boundary_loops[order[rank]]) loop_of[v] = static_cast<int>(rank);
  }
  std::vector<char> is_end(tables.num_vertices(), 0);
  for (EdgeHandle e : mesh.edges()) {
    if (!tree.is_cut[e.idx()]) continue;
    for (int side = 0; side < 2; ++side) {
      const int v = mesh.to_vertex_handle(mesh.halfedge_handle(e, side)).idx();
      if (loop_of[v] >= 0) is_end[v] = 1;
    }
  }
  const MeshTables cut_tables = build_mesh_tables(cut);
  // Face-less halfedges run clockwise: reversed, the surface is on the left.
  std::vector<int> walk(cut_tables.boundary_loops[0].rbegin(), cut_tables.boundary_loops[0].rend());
  const int m = static_cast<int>(walk.size());
  const auto original = [&](int s) { return disk.sliced.to_original_vertex[s]; };
  const auto label = [&](int i) {  // of the walk edge from position i
    const HalfedgeHandle h =
        cut.find_halfedge(cut.vertex_handle(walk[i]), cut.vertex_handle(walk[(i + 1) % m]));
    const int edge = disk.sliced.to_original_edge[cut.edge_handle(h).idx()];
    return tree.is_cut[edge] ? -1 - tree.cut_of_edge[edge] : loop_of[original(walk[i])];
  };
  // Start at the copy of cut 0's first end from which the walk runs along cut 0.
  int start = -1;
  for (int i = 0; i < m && start < 0; ++i) {
    if (original(walk[i]) == tree.first_end[0] && label(i) == -1) start = i;
  }
  if (start < 0) throw TopologyError(std::string(name) + ": the loop-tree cut has no first cut");
  std::rotate(walk.begin(), walk.begin() + start, walk.end());
  disk.walk = walk;
  disk.arc.assign(m + 1, 0.0);
  for (int i = 0; i < m; ++i) {
    const HalfedgeHandle h =
        cut.find_halfedge(cut.vertex_handle(walk[i]), cut.vertex_handle(walk[(i + 1) % m]));
    disk.arc[i + 1] = disk.arc[i] + lengths[cut.edge_handle(h).idx()];
    if (is_end[original(walk[i])]) {
      disk.corners.push_back(i);
      disk.labels.push_back(label(i));
      if (disk.labels.back() >= 0) disk.loop_order.push_back(disk.labels.back());
    }
  }
  return disk;
}

/// The point at hyperbolic distance t d(p, q) from p on the chord from p to q (Klein model).
Eigen::Vector2d klein_geodesic_point(const Eigen::Vector2d& p, const Eigen::Vector2d& q, double t) {
  const auto lift = [](const Eigen::Vector2d& k) -> Eigen::Vector3d {
    return Eigen::Vector3d(1, k.x(), k.y()) / std::sqrt(std::max(1 - k.squaredNorm(), 1e-300));
  };
  const Eigen::Vector3d x = lift(p), y = lift(q);
  const double cosh_d = x[0] * y[0] - x[1] * y[1] - x[2] * y[2];
  const double d = std::acosh(std::max(cosh_d, 1.0));
  if (d < 1e-12) return p + t * (q - p);
  const Eigen::Vector3d z = (std::sinh((1 - t) * d) * x + std::sinh(t * d) * y) / std::sinh(d);
  return Eigen::Vector2d(z[1] / z[0], z[2] / z[0]);
}

/// Steps 4-5: the disk's boundary on `polygon` (arc j on the chord from corner j to j + 1, by
/// the surface's own hyperbolic arc length carried to the chord's), the interior by the
/// mean-value harmonic map of the surface's Klein layout.
Eigen::MatrixX2d polygon_positions(const KleinDisk& disk, const Eigen::MatrixX2d& polygon) {
  const int n = static_cast<int>(disk.sliced.mesh.n_vertices());
  Eigen::MatrixX2d x = Eigen::MatrixX2d::Zero(n, 2);
  std::vector<char> fixed(n, 0);
  const int m = static_cast<int>(disk.walk.size());
  const int k = static_cast<int>(disk.corners.size());
  // A face with three vertices on one side would be flat on a straight side: each side is
  // bowed out by a parabola whose end tangents turn by at most 0.4 of the polygon's turn at
  // either corner (the curve stays strictly convex) and at most 0.05 rad.
  std::vector<double> turn(k);
  for (int j = 0; j < k; ++j) {
    const Eigen::Vector2d p = polygon.row((j + k - 1) % k), q = polygon.row(j),
                          r = polygon.row((j + 1) % k);
    turn[j] = std::atan2(cross2d(q - p, r - q), (q - p).dot(r - q));
  }
  for (int j = 0; j < k; ++j) {
    const int from = disk.corners[j];
    const int to = j + 1 < k ? disk.corners[j + 1] : m;
    const double length = disk.arc[to] - disk.arc[from];
    const Eigen::Vector2d p = polygon.row(j).transpose(), q = polygon.row((j + 1) % k).transpose();
    const Eigen::Vector2d outward = Eigen::Vector2d(q.y() - p.y(), p.x() - q.x());
    const double tilt = std::min(0.05, 0.4 * std::min(turn[j], turn[(j + 1) % k]));
    const double bow = std::tan(tilt) / 4;  // sagitta over the side's length
    for (int i = from; i < to; ++i) {
      const double t = length > 0 ? (disk.arc[i] - disk.arc[from]) / length : 0;
      const Eigen::Vector2d on_side = klein_geodesic_point(p, q, t);
      // The bow by the Euclidean fraction along the side (a parabola over the chord).
      const double e = std::clamp((on_side - p).dot(q - p) / (q - p).squaredNorm(), 0.0, 1.0);
      x.row(disk.walk[i]) = (on_side + 4 * e * (1 - e) * bow * outward).transpose();
      fixed[disk.walk[i]] = 1;
    }
  }
  harmonic_fill(disk.sliced.mesh, disk.chords, fixed, x);
  return x;
}

}  // namespace

void klein_polygon_domains(const Mesh& a, const MeshTables& tables_a, const Mesh& b,
                           const MeshTables& tables_b, const MatchOptions& options,
                           MatchResult& result) {
  result.domain = "klein polygon";
  Stopwatch stage;
  const FlowResult metric_a = hyperbolic_metric(a, tables_a, options, "A", result.a);
  result.a.seconds = stage.lap();
  const FlowResult metric_b = hyperbolic_metric(b, tables_b, options, "B", result.b);
  result.b.seconds = stage.lap();
  // Trees tried in turn until A's and B's polygons have the same sides: each surface's own
  // (Prim's, nearest loop first); B along A's joins, or A along B's (a stretch can change which
  // loop is nearest); the chain c0-c1-...-cn by rank on both (a cut of the chain can close a
  // pocket around a loop between itself and another loop, so it comes last).
  std::optional<KleinDisk> own_a, own_b;
  try {
    own_a = klein_disk(a, tables_a, metric_a, {}, "A");
  } catch (const TopologyError&) {
  }
  result.a.seconds += stage.lap();
  try {
    own_b = klein_disk(b, tables_b, metric_b, {}, "B");
  } catch (const TopologyError&) {
  }
  result.b.seconds += stage.lap();
  std::vector<std::pair<LoopPlan, LoopPlan>> plans;
  if (own_a) plans.push_back({{}, own_a->joins});
  if (own_b) plans.push_back({own_b->joins, {}});
  LoopPlan chain;
  for (int k = 0; k + 1 < static_cast<int>(tables_a.boundary_loops.size()); ++k) {
    chain.push_back({k, k + 1});
  }
  plans.push_back({chain, chain});
  std::optional<KleinDisk> disk_a, disk_b;
  const auto same = [](const KleinDisk& x, const KleinDisk& y) {
    return x.joins == y.joins && x.labels == y.labels;
  };
  if (own_a && own_b && same(*own_a, *own_b)) {
    disk_a = std::move(own_a);
    disk_b = std::move(own_b);
  }
  bool cut_both = own_a && own_b;  // some tree cut both surfaces (but joined them differently)
  std::string blocked;
  for (size_t i = 0; i < plans.size() && !disk_a; ++i) {
    const auto& [plan_a, plan_b] = plans[i];
    try {
      KleinDisk x = plan_a.empty() ? *own_a : klein_disk(a, tables_a, metric_a, plan_a, "A");
      result.a.seconds += stage.lap();
      KleinDisk y = plan_b.empty() ? *own_b : klein_disk(b, tables_b, metric_b, plan_b, "B");
      result.b.seconds += stage.lap();
      cut_both = true;
      if (same(x, y)) {
        disk_a = std::move(x);
        disk_b = std::move(y);
      }
    } catch (const TopologyError& e) {
      blocked = e.what();
    }
  }
  if (!disk_a && cut_both) {
    throw InvalidInputError(
        "the cuts join the boundary loops differently on A and B; the hyperbolic method needs "
        "the same tree of loops");
  }
  if (!disk_a) throw TopologyError(blocked);
  result.a.loop_order = disk_a->loop_order;
  result.b.loop_order = disk_b->loop_order;
  // The common polygon: B's corners, a right-angled hyperbolic polygon, convex in the Klein
  // model (its sides are B's geodesic boundary arcs and the chords between its cut ends).
  const int k = static_cast<int>(disk_b->corners.size());
  Eigen::MatrixX2d polygon(k, 2);
  for (int j = 0; j < k; ++j) polygon.row(j) = disk_b->klein.row(disk_b->walk[disk_b->corners[j]]);
  for (int j = 0; j < k; ++j) {
    const Eigen::Vector2d p = polygon.row(j), q = polygon.row((j + 1) % k),
                          r = polygon.row((j + 2) % k);
    if (cross2d(q - p, r - q) <= 0) {
      throw SolverError("B's right-angled polygon is not convex in the Klein model at corner " +
                        std::to_string((j + 1) % k) + "; the hyperbolic metric is off");
    }
  }
  result.a.positions = polygon_positions(*disk_a, polygon);
  fill_cut_domain(disk_a->sliced, result.a);
  result.a.seconds += stage.lap();
  result.b.positions = polygon_positions(*disk_b, polygon);
  fill_cut_domain(disk_b->sliced, result.b);
  result.b.seconds += stage.lap();
}

}  // namespace ricci::detail

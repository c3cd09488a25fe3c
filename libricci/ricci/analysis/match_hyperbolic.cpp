// Deformable surface matching by the hyperbolic method (Algorithm 9): the hyperbolic metric with
// geodesic boundaries, the loops joined by shortest paths into a tree, the cut disk laid out in
// the Poincaré disk and carried to the Klein model, where geodesics are chords and the
// right-angled polygon is convex; A and B mapped harmonically onto B's polygon.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
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
/// vertices no earlier cut uses and starting at a vertex no cut ends at; loop order[r] is
/// labelled r (the rank of A's loop it pairs with). With an empty `plan`,
/// Prim's tree from c0 (each cut from the loops joined so far to the nearest other loop);
/// otherwise cut k joins plan[k][0] to plan[k][1], whatever is nearer.
/// \throw TopologyError when a loop cannot be reached.
LoopTree join_loops(const Mesh& mesh, const MeshTables& tables, const Eigen::VectorXd& lengths,
                    const std::vector<int>& order, const LoopPlan& plan, const char* name) {
  const int n = tables.num_vertices();
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

/// Steps 2-3 of Algorithm 9 on one surface: the cut, the layout, the polygon's corners; loop
/// order[r] labelled r.
KleinDisk klein_disk(const Mesh& mesh, const MeshTables& tables, const FlowResult& hyperbolic,
                     const std::vector<int>& order, const LoopPlan& plan, const char* name) {
  const LoopTree tree = join_loops(mesh, tables, hyperbolic.lengths, order, plan, name);
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
  // Cut ends: the corners. Label of each loop vertex, for the loop arcs' labels.
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

/// The parameter of each walk vertex on the polygon: j + t on side j, t the surface's own
/// hyperbolic arc length along the side over the side's (as polygon_positions places it).
std::vector<double> polygon_parameters(const KleinDisk& disk) {
  const int m = static_cast<int>(disk.walk.size());
  const int k = static_cast<int>(disk.corners.size());
  std::vector<double> s(static_cast<size_t>(m));
  for (int j = 0; j < k; ++j) {
    const int from = disk.corners[j];
    const int to = j + 1 < k ? disk.corners[j + 1] : m;
    const double length = disk.arc[to] - disk.arc[from];
    for (int i = from; i < to; ++i) {
      s[static_cast<size_t>(i)] = j + (length > 0 ? (disk.arc[i] - disk.arc[from]) / length : 0);
    }
  }
  return s;
}

/// The loops' conformal invariants under the hyperbolic metric with geodesic boundaries, loop
/// order[r] at r: each loop's length and the shortest edge path between two loops.
struct LoopInvariants {
  std::vector<double> lengths;
  Eigen::MatrixXd distances;  ///< Infinite when a path would cross a third loop.
};

LoopInvariants loop_invariants(const Mesh& mesh, const MeshTables& tables,
                               const Eigen::VectorXd& lengths, const std::vector<int>& order) {
  const int loops = static_cast<int>(order.size());
  std::vector<int> loop_of(tables.num_vertices(), -1);
  LoopInvariants invariants;
  invariants.lengths.assign(loops, 0.0);
  for (int r = 0; r < loops; ++r) {
    const std::vector<int>& loop = tables.boundary_loops[order[r]];
    for (size_t i = 0; i < loop.size(); ++i) {
      loop_of[loop[i]] = r;
      const HalfedgeHandle h = mesh.find_halfedge(mesh.vertex_handle(loop[i]),
                                                  mesh.vertex_handle(loop[(i + 1) % loop.size()]));
      invariants.lengths[r] += lengths[mesh.edge_handle(h).idx()];
    }
  }
  invariants.distances = Eigen::MatrixXd::Zero(loops, loops);
  const std::vector<char> used(tables.num_vertices(), 0);
  for (int i = 0; i < loops; ++i) {
    for (int j = i + 1; j < loops; ++j) {
      const std::vector<HalfedgeHandle> path = shortest_path_to_loop(
          mesh, loop_of, lengths, tables.boundary_loops[order[i]], [j](int r) { return r == j; },
          used);
      double d = path.empty() ? std::numeric_limits<double>::infinity() : 0.0;
      for (HalfedgeHandle h : path) d += lengths[mesh.edge_handle(h).idx()];
      invariants.distances(i, j) = invariants.distances(j, i) = d;
    }
  }
  return invariants;
}

/// Pairings of B's loops with A's (pairing[r]: the rank of B's loop paired with A's c_r), by the
/// relative difference of their invariants, sqrt(sum (x_A - x_B)^2 / sum x_A^2) over the loop
/// lengths and the distances between loops: every permutation (up to 8 loops; more: the ranks
/// alone), the closest first, those within `tolerance` of it, at most `most`.
std::vector<std::vector<int>> loop_pairings(const LoopInvariants& a, const LoopInvariants& b,
                                            double tolerance, int most) {
  const int loops = static_cast<int>(a.lengths.size());
  std::vector<int> pairing(loops);
  std::iota(pairing.begin(), pairing.end(), 0);
  if (loops > 8) return {pairing};
  const auto squared = [](double x, double y) {
    if (std::isinf(x) && std::isinf(y)) return 0.0;
    return std::isinf(x) || std::isinf(y) ? std::numeric_limits<double>::infinity()
                                          : (x - y) * (x - y);
  };
  double scale = 0;
  for (int i = 0; i < loops; ++i) {
    scale += a.lengths[i] * a.lengths[i];
    for (int j = i + 1; j < loops; ++j) {
      if (std::isfinite(a.distances(i, j))) scale += a.distances(i, j) * a.distances(i, j);
    }
  }
  std::vector<std::pair<double, std::vector<int>>> all;
  do {  // from the ranks' own pairing, which stays first among equals
    double cost = 0;
    for (int i = 0; i < loops; ++i) {
      cost += squared(a.lengths[i], b.lengths[pairing[i]]);
      for (int j = i + 1; j < loops; ++j) {
        cost += squared(a.distances(i, j), b.distances(pairing[i], pairing[j]));
      }
    }
    all.push_back({std::sqrt(cost / std::max(scale, 1e-300)), pairing});
  } while (std::next_permutation(pairing.begin(), pairing.end()));
  std::stable_sort(all.begin(), all.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<std::vector<int>> pairings;
  for (const auto& [cost, p] : all) {
    if (static_cast<int>(pairings.size()) >= std::max(most, 1) ||
        (!pairings.empty() && !(cost <= all.front().first + tolerance))) {
      break;
    }
    pairings.push_back(p);
  }
  return pairings;
}

/// A's and B's disks cut by one tree of loops (B's loop order_b[r] labelled r), the trees tried
/// in turn until the two polygons have the same sides: each surface's own (Prim's, nearest loop
/// first); B along A's joins, or A along B's (a stretch can change which loop is nearest); the
/// chain c0-c1-...-cn on both (a cut of the chain can close a pocket around a loop between
/// itself and another loop, so it comes last). Empty when none does; `cut_both` is set when some
/// tree cut both surfaces, `blocked` says why the last tree failed to cut one.
std::optional<std::pair<KleinDisk, KleinDisk>> cut_alike(
    const Mesh& a, const MeshTables& tables_a, const FlowResult& metric_a,
    const std::vector<int>& order_a, const std::optional<KleinDisk>& own_a, const Mesh& b,
    const MeshTables& tables_b, const FlowResult& metric_b, const std::vector<int>& order_b,
    bool& cut_both, std::string& blocked) {
  std::optional<KleinDisk> own_b;
  try {
    own_b = klein_disk(b, tables_b, metric_b, order_b, {}, "B");
  } catch (const TopologyError&) {
  }
  const auto same = [](const KleinDisk& x, const KleinDisk& y) {
    return x.joins == y.joins && x.labels == y.labels;
  };
  if (own_a && own_b) {
    cut_both = true;
    if (same(*own_a, *own_b)) return std::make_pair(*own_a, std::move(*own_b));
  }
  std::vector<std::pair<LoopPlan, LoopPlan>> plans;
  if (own_a) plans.push_back({{}, own_a->joins});
  if (own_b) plans.push_back({own_b->joins, {}});
  LoopPlan chain;
  for (int k = 0; k + 1 < static_cast<int>(order_a.size()); ++k) chain.push_back({k, k + 1});
  plans.push_back({chain, chain});
  for (const auto& [plan_a, plan_b] : plans) {
    try {
      KleinDisk x =
          plan_a.empty() ? *own_a : klein_disk(a, tables_a, metric_a, order_a, plan_a, "A");
      KleinDisk y =
          plan_b.empty() ? *own_b : klein_disk(b, tables_b, metric_b, order_b, plan_b, "B");
      cut_both = true;
      if (same(x, y)) return std::make_pair(std::move(x), std::move(y));
    } catch (const TopologyError& e) {
      blocked = e.what();
    }
  }
  return std::nullopt;
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
  // B's loops paired with A's by their conformal invariants (3D length ranks change under a
  // deformation where loops have about one length); of the close pairings, the smallest d_g.
  const std::vector<int> order_a = loops_by_length(a, tables_a);
  const std::vector<int> ranks_b = loops_by_length(b, tables_b);
  const std::vector<std::vector<int>> pairings =
      loop_pairings(loop_invariants(a, tables_a, metric_a.lengths, order_a),
                    loop_invariants(b, tables_b, metric_b.lengths, ranks_b),
                    options.loop_invariant_tolerance, options.loop_pairings);
  std::optional<KleinDisk> own_a;
  try {
    own_a = klein_disk(a, tables_a, metric_a, order_a, {}, "A");
  } catch (const TopologyError&) {
  }
  result.a.seconds += stage.lap();
  MatchResult best;
  bool cut_both = false;  // some tree cut both surfaces (but joined them differently)
  std::string blocked, not_convex;
  for (const std::vector<int>& pairing : pairings) {
    std::vector<int> order_b(pairing.size());
    for (size_t r = 0; r < pairing.size(); ++r) order_b[r] = ranks_b[pairing[r]];
    const auto disks = cut_alike(a, tables_a, metric_a, order_a, own_a, b, tables_b, metric_b,
                                 order_b, cut_both, blocked);
    if (!disks) continue;
    const auto& [disk_a, disk_b] = *disks;
    // The common polygon: B's corners, a right-angled hyperbolic polygon, convex in the Klein
    // model (its sides are B's geodesic boundary arcs and the chords between its cut ends).
    const int k = static_cast<int>(disk_b.corners.size());
    Eigen::MatrixX2d polygon(k, 2);
    for (int j = 0; j < k; ++j) polygon.row(j) = disk_b.klein.row(disk_b.walk[disk_b.corners[j]]);
    for (int j = 0; j < k && not_convex.empty(); ++j) {
      const Eigen::Vector2d p = polygon.row(j), q = polygon.row((j + 1) % k),
                            r = polygon.row((j + 2) % k);
      if (cross2d(q - p, r - q) <= 0) {
        not_convex = "B's right-angled polygon is not convex in the Klein model at corner " +
                     std::to_string((j + 1) % k) + "; the hyperbolic metric is off";
      }
    }
    if (!not_convex.empty()) continue;
    MatchResult trial = result;
    trial.a.loop_order = disk_a.loop_order;
    trial.b.loop_order = disk_b.loop_order;
    trial.b.positions = polygon_positions(disk_b, polygon);
    fill_cut_domain(disk_b.sliced, trial.b);
    trial.a.positions =
        fill_inside(disk_a.sliced.mesh, disk_a.chords, disk_a.walk, polygon_parameters(disk_a),
                    disk_b.walk, polygon_parameters(disk_b), trial.b.positions, k);
    fill_cut_domain(disk_a.sliced, trial.a);
    evaluate_map(a, b, tables_a, tables_b, trial, false);
    if (best.map.empty() || trial.shape_error < best.shape_error) best = std::move(trial);
  }
  if (best.map.empty()) {
    if (!not_convex.empty()) throw SolverError(not_convex);
    if (cut_both) {
      throw InvalidInputError(
          "the cuts join the boundary loops differently on A and B; the hyperbolic method needs "
          "the same tree of loops");
    }
    throw TopologyError(blocked);
  }
  best.b.seconds += stage.lap();  // B's cuts and both maps, for each pairing tried
  result = std::move(best);
}

}  // namespace ricci::detail

// Algorithm 8, step 4: the cone star, vertex-disjoint shortest rays from the feature vertex to
// each boundary loop (in rank order, nearest loop first, or leaving the feature in a given
// cyclic order), and the disk the surface is cut into along them.
#include <algorithm>
#include <numeric>
#include <string>
#include <utility>

#include "ricci/analysis/match_internal.h"
#include "ricci/analysis/module_internal.h"
#include "ricci/mesh/errors.h"

namespace ricci::detail {

namespace {

/// The ray from interior vertex p to boundary loop `target` avoiding the `used` vertices of
/// earlier rays, ending at its first vertex on the loop; marks its vertices but p used.
/// \throw TopologyError when the loop cannot be reached.
std::vector<HalfedgeHandle> ray_to_loop(const Mesh& mesh, const std::vector<int>& loop_of,
                                        const EdgeLengths& lengths, int p, int target,
                                        std::vector<char>& used) {
  const std::vector<HalfedgeHandle> path = detail::shortest_path_to_loop(
      mesh, loop_of, lengths, {p}, [target](int loop) { return loop == target; }, used);
  if (path.empty()) {
    throw TopologyError("no path from the feature vertex reaches boundary loop " +
                        std::to_string(target) + " without crossing the other cuts");
  }
  for (HalfedgeHandle h : path) used[mesh.to_vertex_handle(h).idx()] = 1;
  return path;
}

/// The cut along the rays (`is_cut` by edge; `end_rank`: by vertex, the rank of the loop a ray
/// ends on there, else -1): slice, boundary walk from the copy of p whose ray goes to c0, arcs.
/// \throw TopologyError when the cut is not a disk or its walk not out-around-back per ray.
Star star_from_rays(const Mesh& mesh, int p, const EdgeLengths& flat,
                    const std::vector<char>& is_cut, const std::vector<int>& end_rank,
                    const char* name) {
  const int loops = static_cast<int>(
      std::count_if(end_rank.begin(), end_rank.end(), [](int rank) { return rank >= 0; }));
  Star star;
  star.sliced = slice_along(mesh, is_cut);
  check_disk(star.sliced, "cone-star cut");
  star.lengths = sliced_edge_lengths(star.sliced, flat);
  const MeshTables cut_tables = build_mesh_tables(star.sliced.mesh);
  // Face-less halfedges run clockwise: reversed, the surface is on the left.
  std::vector<int> walk(cut_tables.boundary_loops[0].rbegin(), cut_tables.boundary_loops[0].rend());
  const auto original = [&](int s) { return star.sliced.to_original_vertex[s]; };
  const auto is_corner = [&](int s) { return original(s) == p || end_rank[original(s)] >= 0; };
  // Start at the copy of p whose next arc goes out to c0.
  const int m = static_cast<int>(walk.size());
  int start = -1;
  for (int i = 0; i < m && start < 0; ++i) {
    if (original(walk[i]) != p) continue;
    int j = (i + 1) % m;
    while (!is_corner(walk[j])) j = (j + 1) % m;
    if (end_rank[original(walk[j])] == 0) start = i;
  }
  if (start < 0) throw TopologyError(std::string(name) + ": the cone star has no ray to c0");
  std::rotate(walk.begin(), walk.begin() + start, walk.end());
  star.walk = walk;
  star.arc.assign(m + 1, 0.0);
  for (int i = 0; i < m; ++i) {
    const HalfedgeHandle h = star.sliced.mesh.find_halfedge(
        star.sliced.mesh.vertex_handle(walk[i]), star.sliced.mesh.vertex_handle(walk[(i + 1) % m]));
    star.arc[i + 1] = star.arc[i] + star.lengths[star.sliced.mesh.edge_handle(h).idx()];
    if (is_corner(walk[i])) star.corners.push_back(i);
  }
  // The walk is p, e_k, e_k, p, e_j, e_j, ...: out along a ray, around its loop, back.
  bool pattern = static_cast<int>(star.corners.size()) == 3 * loops;
  for (int r = 0; pattern && r < loops; ++r) {
    const int a = original(walk[star.corners[3 * r]]);
    const int b = original(walk[star.corners[3 * r + 1]]);
    const int c = original(walk[star.corners[3 * r + 2]]);
    pattern = a == p && b == c && end_rank[b] >= 0;
    if (pattern) star.loop_order.push_back(end_rank[b]);
  }
  if (!pattern) {
    throw TopologyError(std::string(name) + ": the cut disk's boundary is not out-around-back " +
                        "along each ray");
  }
  const Eigen::VectorXd lengths_3d = sliced_edge_lengths(star.sliced, mesh_edge_lengths(mesh));
  star.param_arc.assign(m + 1, 0.0);
  for (int i = 0, j = 0; i < m; ++i) {
    while (j + 1 < static_cast<int>(star.corners.size()) && star.corners[j + 1] <= i) ++j;
    const HalfedgeHandle h = star.sliced.mesh.find_halfedge(
        star.sliced.mesh.vertex_handle(walk[i]), star.sliced.mesh.vertex_handle(walk[(i + 1) % m]));
    const int e = star.sliced.mesh.edge_handle(h).idx();
    star.param_arc[i + 1] = star.param_arc[i] + (j % 3 == 1 ? star.lengths[e] : lengths_3d[e]);
  }
  return star;
}

}  // namespace

/// Algorithm 8, step 4 and the cut: rays, slice, boundary walk, under the flat metric `flat`.
/// The rays are taken in rank order, then (if one is blocked) nearest loop first;
/// `reach_first` swaps the two.
/// \throw TopologyError when the rays cannot be made vertex-disjoint or the cut is not a disk.
Star cone_star(const Mesh& mesh, const MeshTables& tables, int p, const EdgeLengths& flat,
               const char* name, bool reach_first) {
  const int n = tables.num_vertices();
  const int loops = static_cast<int>(tables.boundary_loops.size());
  const std::vector<int> order = detail::loops_by_length(mesh, tables);
  // Step 4: one ray from p to each loop, longest loop first, vertex-disjoint.
  std::vector<int> loop_of(n, -1);
  for (int k = 0; k < loops; ++k) {
    for (int v : tables.boundary_loops[k]) loop_of[v] = k;
  }
  // Rays are taken in rank order (the same on both surfaces), then, if one is blocked, nearest
  // loop first (fewest detours around earlier rays).
  std::vector<double> reach(loops);
  for (int rank = 0; rank < loops; ++rank) {
    std::vector<char> none(n, 0);
    none[p] = 1;
    double length = 0;
    for (HalfedgeHandle h : ray_to_loop(mesh, loop_of, flat, p, order[rank], none)) {
      length += flat[mesh.edge_handle(h).idx()];
    }
    reach[rank] = length;
  }
  std::vector<int> by_reach(loops), by_rank(loops);
  for (int rank = 0; rank < loops; ++rank) by_reach[rank] = by_rank[rank] = rank;
  std::stable_sort(by_reach.begin(), by_reach.end(),
                   [&](int x, int y) { return reach[x] < reach[y]; });
  std::vector<char> is_cut;
  std::vector<int> end_rank;
  for (int attempt = 0; attempt < 2; ++attempt) {
    const std::vector<int>& ranks = (attempt == 0) != reach_first ? by_rank : by_reach;
    std::vector<char> used(n, 0);
    used[p] = 1;
    is_cut.assign(mesh.n_edges(), 0);
    end_rank.assign(n, -1);
    try {
      for (int rank : ranks) {
        const auto path = ray_to_loop(mesh, loop_of, flat, p, order[rank], used);
        for (HalfedgeHandle h : path) is_cut[mesh.edge_handle(h).idx()] = 1;
        end_rank[mesh.to_vertex_handle(path.back()).idx()] = rank;
      }
      break;
    } catch (const TopologyError&) {
      if (attempt == 0) continue;
      throw TopologyError(std::string(name) + ": no vertex-disjoint shortest paths join the " +
                          "feature vertex " + std::to_string(p) +
                          " to every boundary loop; choose another feature vertex");
    }
  }
  return star_from_rays(mesh, p, flat, is_cut, end_rank, name);
}

namespace {

/// Positions in p's fan of v neighbours for rays to the loop ranks `order`, k of them: order[0]
/// at `start`, the others `direction` round the fan from it in order, within one turn, each as
/// near as can be (cyclic distance in the fan) to `natural[rank]`, the first step of its free
/// ray. Returns the summed distance and the positions.
std::pair<int, std::vector<int>> fan_positions(const std::vector<int>& order,
                                               const std::vector<int>& natural, int v, int start,
                                               int direction) {
  const int k = static_cast<int>(order.size());
  const auto at = [&](int offset) { return ((start + direction * offset) % v + v) % v; };
  const auto cost = [&](int j, int offset) {
    const int d = std::abs(at(offset) - natural[order[j]]);
    return std::min(d, v - d);
  };
  constexpr int kNone = 1 << 29;
  // best[j][o]: the least cost of order[0..j] with order[j] at offset o; from[j][o] the offset
  // of order[j - 1] there.
  std::vector<std::vector<int>> best(k, std::vector<int>(v, kNone)), from(k, std::vector<int>(v));
  best[0][0] = cost(0, 0);
  for (int j = 1; j < k; ++j) {
    int low = kNone, low_at = -1;
    for (int o = 1; o < v; ++o) {
      if (best[j - 1][o - 1] < low) low = best[j - 1][o - 1], low_at = o - 1;
      if (low < kNone) best[j][o] = low + cost(j, o), from[j][o] = low_at;
    }
  }
  const auto last = std::min_element(best[k - 1].begin(), best[k - 1].end());
  std::vector<int> positions(k);
  int o = static_cast<int>(last - best[k - 1].begin());
  for (int j = k - 1; j >= 0; --j) {
    positions[j] = at(o);
    if (j > 0) o = from[j][o];
  }
  return {*last, positions};
}

}  // namespace

Star ordered_star(const Mesh& mesh, const MeshTables& tables, int p, const EdgeLengths& flat,
                  const std::vector<int>& order, const char* name) {
  const int n = tables.num_vertices();
  const int loops = static_cast<int>(tables.boundary_loops.size());
  const std::vector<int> rank_loop = loops_by_length(mesh, tables);
  std::vector<int> loop_of(n, -1);
  for (int k = 0; k < loops; ++k) {
    for (int v : tables.boundary_loops[k]) loop_of[v] = k;
  }
  std::vector<int> fan;
  for (VertexHandle q : mesh.vv_range(mesh.vertex_handle(p))) fan.push_back(q.idx());
  const int v = static_cast<int>(fan.size());
  const auto text = [&] {
    std::string t;
    for (int rank : order) t += (t.empty() ? "c" : " c") + std::to_string(rank);
    return std::string(name) + ": no vertex-disjoint rays leave the feature vertex " +
           std::to_string(p) + " towards the loops in the order " + t;
  };
  if (v < loops || static_cast<int>(order.size()) != loops) throw TopologyError(text());
  // Each loop's free ray: its first step in the fan and its length.
  std::vector<int> natural(loops);
  std::vector<double> reach(loops, 0.0);
  for (int rank = 0; rank < loops; ++rank) {
    std::vector<char> none(n, 0);
    none[p] = 1;
    const auto path = ray_to_loop(mesh, loop_of, flat, p, rank_loop[rank], none);
    natural[rank] = static_cast<int>(
        std::find(fan.begin(), fan.end(), mesh.to_vertex_handle(path.front()).idx()) - fan.begin());
    for (HalfedgeHandle h : path) reach[rank] += flat[mesh.edge_handle(h).idx()];
  }
  std::vector<std::pair<int, std::vector<int>>> assignments;
  for (int direction : {1, -1}) {
    for (int start = 0; start < v; ++start) {
      assignments.push_back(fan_positions(order, natural, v, start, direction));
    }
  }
  std::stable_sort(assignments.begin(), assignments.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  // Nearest loop first (the short rays take the room by p before the long ones wind round),
  // then farthest first.
  std::vector<int> nearest(loops);
  std::iota(nearest.begin(), nearest.end(), 0);
  std::stable_sort(nearest.begin(), nearest.end(),
                   [&](int x, int y) { return reach[order[x]] < reach[order[y]]; });
  const std::vector<int> farthest(nearest.rbegin(), nearest.rend());
  for (const std::vector<int>* sequence_of : {&std::as_const(nearest), &farthest}) {
    const std::vector<int>& sequence = *sequence_of;
    for (const auto& [cost, positions] : assignments) {
      std::vector<char> used(n, 0), is_cut(mesh.n_edges(), 0);
      std::vector<int> end_rank(n, -1);
      used[p] = 1;
      for (int position : positions) used[fan[position]] = 1;  // each start kept for its ray
      bool built = true;
      for (int j : sequence) {
        const int start = fan[positions[j]], rank = order[j];
        const int target = rank_loop[rank];
        is_cut[mesh.edge_handle(
                       mesh.find_halfedge(mesh.vertex_handle(p), mesh.vertex_handle(start)))
                   .idx()] = 1;
        int end = start;
        if (loop_of[start] >= 0) {
          built = loop_of[start] == target;
        } else {
          const auto path = shortest_path_to_loop(
              mesh, loop_of, flat, {start}, [target](int loop) { return loop == target; }, used);
          built = !path.empty();
          for (HalfedgeHandle h : path) {
            is_cut[mesh.edge_handle(h).idx()] = 1;
            used[mesh.to_vertex_handle(h).idx()] = 1;
          }
          if (built) end = mesh.to_vertex_handle(path.back()).idx();
        }
        if (!built) break;
        end_rank[end] = rank;
      }
      if (!built) {
        continue;
      }
      try {
        Star star = star_from_rays(mesh, p, flat, is_cut, end_rank, name);
        if (star.loop_order == order) return star;
      } catch (const TopologyError&) {
      }
    }
  }
  throw TopologyError(text());
}

}  // namespace ricci::detail

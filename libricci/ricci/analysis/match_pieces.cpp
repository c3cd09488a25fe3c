// Algorithm 8, steps 5-8: the cone star's disk cut into convex pieces along shortest loops round
// the boundary loops, each pair of pieces mapped harmonically onto one convex polygon, the maps
// glued along the loops; and the arc parametrisation every convex piece of the cone star uses.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

#include "ricci/analysis/match_internal.h"
#include "ricci/mesh/errors.h"
#include "ricci/metric/mesh_tables.h"

namespace ricci::detail {

std::vector<double> arc_fractions(const ArcWalk& w) {
  std::vector<double> fractions;
  const size_t k = w.corners.size();
  for (size_t j = 0; j < k; ++j) {
    const int from = w.corners[j];
    const int to = j + 1 < k ? w.corners[j + 1] : static_cast<int>(w.walk.size());
    fractions.push_back((w.arc[to] - w.arc[from]) / w.arc.back());
  }
  return fractions;
}

std::vector<double> common_extents(const ArcWalk& a, const ArcWalk& b) {
  const std::vector<double> fa = arc_fractions(a), fb = arc_fractions(b);
  std::vector<double> extents(fa.size());
  for (size_t j = 0; j < fa.size(); ++j) {
    extents[j] = 0.25 * (fa[j] + fb[j]) + 0.5 / static_cast<double>(fa.size());
  }
  return extents;
}

std::vector<double> arc_parameters(const ArcWalk& w, const std::vector<double>& extents) {
  const int m = static_cast<int>(w.walk.size());
  std::vector<double> s(static_cast<size_t>(m));
  double start = 0;
  for (size_t j = 0; j < w.corners.size(); ++j) {
    const int from = w.corners[j];
    const int to = j + 1 < w.corners.size() ? w.corners[j + 1] : m;
    const double length = w.param_arc[to] - w.param_arc[from];
    for (int i = from; i < to; ++i) {
      const double t = length > 0 ? (w.param_arc[i] - w.param_arc[from]) / length : 0;
      s[static_cast<size_t>(i)] = start + t * extents[j];
    }
    start += extents[j];
  }
  return s;
}

void place_on_circle(const ArcWalk& w, const std::vector<double>& parameters,
                     const Eigen::Vector2d& centre, Eigen::MatrixX2d& x, std::vector<char>& fixed) {
  for (size_t i = 0; i < w.walk.size(); ++i) {
    const double angle = 2 * M_PI * parameters[i];
    x.row(w.walk[i]) << centre.x() + std::cos(angle), centre.y() + std::sin(angle);
    fixed[w.walk[i]] = 1;
  }
}

namespace {

enum class ArcKind : char { ray, loop, gamma };

/// One convex piece of a surface cut along its rays and gammas.
struct Piece : ArcWalk {
  int triple = -1;  ///< The star's triple (ray, loop, ray back) whose loop it holds; -1 central.
  std::vector<ArcKind> kinds;  ///< By arc.
};

/// The shortest edge path (under `lengths`) in the disk from boundary vertex `from` to boundary
/// vertex `to` through vertices not `blocked`; empty when there is none.
std::vector<int> interior_path(const Mesh& disk, const Eigen::VectorXd& lengths,
                               const std::vector<char>& blocked, int from, int to) {
  const int n = static_cast<int>(disk.n_vertices());
  std::vector<double> distance(n, std::numeric_limits<double>::infinity());
  std::vector<int> previous(n, -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  distance[from] = 0;
  queue.push({0.0, from});
  while (!queue.empty()) {
    const auto [d, u] = queue.top();
    queue.pop();
    if (d > distance[u]) continue;
    if (u == to) break;
    for (HalfedgeHandle h : disk.voh_range(disk.vertex_handle(u))) {
      const int w = disk.to_vertex_handle(h).idx();
      // The path leaves `from` and reaches `to` through unblocked vertices only.
      if (w == to ? u == from : blocked[w]) continue;
      const double next = d + lengths[disk.edge_handle(h).idx()];
      if (next < distance[w]) {
        distance[w] = next;
        previous[w] = u;
        queue.push({next, w});
      }
    }
  }
  if (previous[to] < 0) return {};
  std::vector<int> path = {to};
  while (path.back() != from) path.push_back(previous[path.back()]);
  std::reverse(path.begin(), path.end());
  return path;
}

/// Step 5: for each triple r > 0 of the star's walk, a shortest loop round its boundary loop
/// through a vertex x of its ray (the out copy to the back copy, through the disk's interior,
/// vertex-disjoint from the others), tried first at the ray's 3D middle, then towards the loop,
/// then towards p, last next to the loop. By triple; empty where none was found (always for
/// triple 0; and where a ray to another loop runs one edge from this loop, as shortest rays
/// hug the holes they pass, no path goes round it).
std::vector<std::vector<int>> gammas(const Star& star) {
  const Mesh& disk = star.sliced.mesh;
  const int m = static_cast<int>(star.walk.size());
  const size_t triples = star.corners.size() / 3;
  std::vector<char> blocked(disk.n_vertices(), 0);
  for (int v : star.walk) blocked[v] = 1;
  std::vector<std::vector<int>> out(triples);
  for (size_t r = 1; r < triples; ++r) {
    const int p_out = star.corners[3 * r], end = star.corners[3 * r + 1];
    const int p_back = 3 * r + 3 < star.corners.size() ? star.corners[3 * r + 3] : m;
    const int rays = end - p_out;  // edges of the ray
    if (rays < 2) continue;
    const double half = 0.5 * (star.param_arc[end] + star.param_arc[p_out]);
    int middle = 1;
    for (int i = 1; i < rays; ++i) {
      if (std::abs(star.param_arc[p_out + i] - half) <
          std::abs(star.param_arc[p_out + middle] - half)) {
        middle = i;
      }
    }
    // At most 8 tries; the vertex next to the loop last (its gamma hugs the loop at one ring).
    std::vector<int> tries;
    for (int i = middle; i < rays - 1; ++i) tries.push_back(i);
    for (int i = middle - 1; i >= 1; --i) tries.push_back(i);
    if (tries.size() > 7) tries.resize(7);
    tries.push_back(rays - 1);
    for (int i : tries) {
      const int x_out = star.walk[p_out + i], x_back = star.walk[p_back - i];
      if (star.sliced.to_original_vertex[x_out] != star.sliced.to_original_vertex[x_back]) break;
      std::vector<int> path = interior_path(disk, star.lengths, blocked, x_out, x_back);
      if (path.size() < 3) continue;
      for (size_t k = 1; k + 1 < path.size(); ++k) blocked[path[k]] = 1;
      out[r] = std::move(path);
      break;
    }
  }
  return out;
}

/// The mesh cut along the star's rays and the gammas kept, and its pieces: central piece first
/// (from the copy of p before triple 0's ray), then one per gamma (from the copy of x before its
/// ray part), each with its corners and arc kinds.
struct Cut {
  SlicedMesh sliced;
  Eigen::VectorXd flat;  ///< By sliced edge.
  std::vector<Piece> pieces;
};

/// What tells the corners and arcs of a piece's walk apart, by original vertex or edge.
struct Marks {
  int p = -1;
  std::vector<int> triple_of_end;  ///< The triple whose ray ends here, else -1.
  std::vector<char> is_x;          ///< A kept gamma's x.
  std::vector<char> is_ray;        ///< By original edge.
};

/// One piece from its boundary loop (as build_mesh_tables gives it) in the cut mesh.
/// \throw TopologyError when the walk has no start corner or a gamma's piece is not x, ray,
///        loop, ray, gamma.
Piece piece_of(const std::vector<int>& loop, const Mesh& mesh, const Cut& cut,
               const Eigen::VectorXd& lengths_3d, const Marks& marks) {
  const Mesh& pieces = cut.sliced.mesh;
  // Face-less halfedges run clockwise: reversed, the surface is on the left.
  std::vector<int> walk(loop.rbegin(), loop.rend());
  const int m = static_cast<int>(walk.size());
  const auto to_original = [&](int s) { return cut.sliced.to_original_vertex[s]; };
  const auto edge_of = [&](int i) {
    return pieces.edge_handle(pieces.find_halfedge(pieces.vertex_handle(walk[i]),
                                                   pieces.vertex_handle(walk[(i + 1) % m])));
  };
  const auto kind_of = [&](int i) {
    const EdgeHandle e = mesh.edge_handle(cut.sliced.to_original_edge[edge_of(i).idx()]);
    return mesh.is_boundary(e)     ? ArcKind::loop
           : marks.is_ray[e.idx()] ? ArcKind::ray
                                   : ArcKind::gamma;
  };
  const auto is_corner = [&](int i) {
    const int v = to_original(walk[i]);
    return v == marks.p || marks.triple_of_end[v] >= 0 || marks.is_x[v];
  };
  // The start: central, the copy of p whose ray ends on triple 0's loop; else the x whose next
  // arc is its ray part.
  Piece piece;
  int start = -1;
  for (int i = 0; i < m && start < 0; ++i) {
    if (!is_corner(i)) continue;
    int j = (i + 1) % m;
    while (!is_corner(j)) j = (j + 1) % m;
    const int v = to_original(walk[i]), w = to_original(walk[j]);
    if (v == marks.p && marks.triple_of_end[w] == 0) start = i;
    if (marks.is_x[v] && kind_of(i) == ArcKind::ray && marks.triple_of_end[w] >= 0) {
      start = i;
      piece.triple = marks.triple_of_end[w];
    }
  }
  if (start < 0) throw TopologyError("cone pieces: a piece without its start corner");
  if (piece.triple >= 0) {
    // x, out along the ray, round the loop, back along the ray, the gamma back to x.
    piece.kinds = {ArcKind::ray, ArcKind::loop, ArcKind::ray, ArcKind::gamma};
  }
  std::rotate(walk.begin(), walk.begin() + start, walk.end());
  piece.arc.assign(m + 1, 0.0);
  piece.param_arc.assign(m + 1, 0.0);
  for (int i = 0; i < m; ++i) {
    if (is_corner(i)) {
      const ArcKind kind = kind_of(i);
      if (piece.triple >= 0 &&
          (piece.corners.size() >= 4 || piece.kinds[piece.corners.size()] != kind)) {
        throw TopologyError("cone pieces: a gamma encloses more than its loop");
      }
      piece.corners.push_back(i);
      if (piece.triple < 0) piece.kinds.push_back(kind);
    }
    const int e = edge_of(i).idx();
    piece.arc[i + 1] = piece.arc[i] + cut.flat[e];
    piece.param_arc[i + 1] =
        piece.param_arc[i] +
        (piece.kinds[piece.corners.size() - 1] == ArcKind::ray ? lengths_3d[e] : cut.flat[e]);
  }
  if (piece.triple >= 0 && piece.corners.size() != 4) {
    throw TopologyError("cone pieces: a gamma encloses more than its loop");
  }
  piece.walk = std::move(walk);
  return piece;
}

/// The mesh cut along the star's rays and the gammas `kept` (by triple), and its pieces.
/// \throw TopologyError when the pieces are not disks or not of the expected pattern.
Cut cut_pieces(const Mesh& mesh, const Star& star, const EdgeLengths& flat,
               const std::vector<std::vector<int>>& gamma, const std::vector<char>& kept) {
  const auto original = [&](int s) { return star.sliced.to_original_vertex[s]; };
  Marks marks;
  marks.p = original(star.walk[0]);
  marks.triple_of_end.assign(mesh.n_vertices(), -1);
  marks.is_x.assign(mesh.n_vertices(), 0);
  marks.is_ray.assign(mesh.n_edges(), 0);
  for (const CutEdgeSides& sides : star.sliced.cut_sides) marks.is_ray[sides.edge.idx()] = 1;
  std::vector<char> is_cut = marks.is_ray;
  const Mesh& disk = star.sliced.mesh;
  int expected = 1;
  for (size_t r = 0; r < gamma.size(); ++r) {
    marks.triple_of_end[original(star.walk[star.corners[3 * r + 1]])] = static_cast<int>(r);
    if (!kept[r]) continue;
    ++expected;
    marks.is_x[original(gamma[r].front())] = 1;
    for (size_t k = 0; k + 1 < gamma[r].size(); ++k) {
      const HalfedgeHandle h =
          disk.find_halfedge(disk.vertex_handle(gamma[r][k]), disk.vertex_handle(gamma[r][k + 1]));
      is_cut[star.sliced.to_original_edge[disk.edge_handle(h).idx()]] = 1;
    }
  }
  Cut cut;
  cut.sliced = slice_along(mesh, is_cut);
  if (cut.sliced.component_count != expected || cut.sliced.boundary_loop_count != expected ||
      cut.sliced.euler_characteristic != expected) {
    throw TopologyError("cone pieces: the gammas do not cut the disk into disks");
  }
  cut.flat = sliced_edge_lengths(cut.sliced, flat);
  const Eigen::VectorXd lengths_3d = sliced_edge_lengths(cut.sliced, mesh_edge_lengths(mesh));
  for (const std::vector<int>& loop : build_mesh_tables(cut.sliced.mesh).boundary_loops) {
    cut.pieces.push_back(piece_of(loop, mesh, cut, lengths_3d, marks));
  }
  std::sort(cut.pieces.begin(), cut.pieces.end(),
            [](const Piece& x, const Piece& y) { return x.triple < y.triple; });
  return cut;
}

}  // namespace

void cone_pieces(const Mesh& a, const Star& star_a, const EdgeLengths& flat_a, const Mesh& b,
                 const Star& star_b, const EdgeLengths& flat_b, MatchResult& result) {
  const std::vector<std::vector<int>> gamma_a = gammas(star_a), gamma_b = gammas(star_b);
  std::vector<char> kept(gamma_a.size(), 0);
  bool any = false;
  for (size_t r = 0; r < kept.size(); ++r) {
    kept[r] = !gamma_a[r].empty() && r < gamma_b.size() && !gamma_b[r].empty();
    any = any || kept[r];
  }
  if (!any || gamma_a.size() != gamma_b.size()) {
    throw TopologyError("cone pieces: no loop has its gamma on both surfaces");
  }
  const Cut cut_a = cut_pieces(a, star_a, flat_a, gamma_a, kept);
  const Cut cut_b = cut_pieces(b, star_b, flat_b, gamma_b, kept);
  const size_t count = cut_a.pieces.size();
  for (size_t k = 0; k < count; ++k) {
    if (cut_b.pieces.size() != count || cut_a.pieces[k].triple != cut_b.pieces[k].triple ||
        cut_a.pieces[k].kinds != cut_b.pieces[k].kinds) {
      throw TopologyError("cone pieces: the pieces of A and B differ");
    }
  }
  const int nb = static_cast<int>(cut_b.sliced.mesh.n_vertices());
  const int na = static_cast<int>(cut_a.sliced.mesh.n_vertices());
  Eigen::MatrixX2d xb = Eigen::MatrixX2d::Zero(nb, 2), xa = Eigen::MatrixX2d::Zero(na, 2);
  std::vector<char> fixed_b(nb, 0), fixed_a(na, 0);
  std::vector<std::vector<double>> params_a(count), params_b(count);
  for (size_t k = 0; k < count; ++k) {
    const std::vector<double> extents = common_extents(cut_a.pieces[k], cut_b.pieces[k]);
    params_a[k] = arc_parameters(cut_a.pieces[k], extents);
    params_b[k] = arc_parameters(cut_b.pieces[k], extents);
    place_on_circle(cut_b.pieces[k], params_b[k], Eigen::Vector2d(3.0 * static_cast<double>(k), 0),
                    xb, fixed_b);
  }
  harmonic_fill(cut_b.sliced.mesh, cut_b.flat, fixed_b, xb);
  for (size_t k = 0; k < count; ++k) {
    place_on_polygon(cut_a.pieces[k].walk, params_a[k], cut_b.pieces[k].walk, params_b[k], xb, 1.0,
                     xa, fixed_a);
  }
  harmonic_fill(cut_a.sliced.mesh, cut_a.flat, fixed_a, xa);
  result.a.positions = std::move(xa);
  result.b.positions = std::move(xb);
  fill_cut_domain(cut_a.sliced, result.a);
  fill_cut_domain(cut_b.sliced, result.b);
  result.pieces = static_cast<int>(count);
}

}  // namespace ricci::detail

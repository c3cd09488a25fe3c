// Transition maps between overlapping charts and the side pairings of the cut graph's arcs.
#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "ricci/atlas/chart_develop.h"
#include "ricci/mesh/topology_util.h"
#include "ricci/util/parallel.h"

namespace ricci::detail {
namespace {

int local_index(const std::vector<int>& sorted, int face) {
  const auto it = std::lower_bound(sorted.begin(), sorted.end(), face);
  return it != sorted.end() && *it == face ? static_cast<int>(it - sorted.begin()) : -1;
}

/// Chart vertices of the two ends of halfedge hs[k] of a face in `chart` (row `row`): from, to.
std::pair<int, int> edge_copies(const Chart& chart, int row, int k) {
  return {chart.corners(row, (k + 2) % 3), chart.corners(row, k)};
}

/// True when faces f and g (sharing the edge of f's k-th halfedge) are glued along it in `chart`.
bool glued(const Mesh& mesh, const Chart& chart, int f, int k, int g) {
  const auto hs = face_halfedges(mesh, FaceHandle(f));
  const auto gs = face_halfedges(mesh, FaceHandle(g));
  const auto o = mesh.opposite_halfedge_handle(hs[k]);
  const int m = gs[0] == o ? 0 : (gs[1] == o ? 1 : 2);
  const auto [f_from, f_to] = edge_copies(chart, chart.slot(f), k);
  const auto [g_from, g_to] = edge_copies(chart, chart.slot(g), m);
  return f_from == g_to && f_to == g_from;
}

/// The pairs sorted and deduplicated, as two lists.
std::pair<std::vector<int>, std::vector<int>> unzip_unique(std::vector<std::pair<int, int>> pairs) {
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  std::pair<std::vector<int>, std::vector<int>> lists;
  for (const auto& [a, b] : pairs) {
    lists.first.push_back(a);
    lists.second.push_back(b);
  }
  return lists;
}

/// Below this extent relative to its coordinates' magnitude, a point set's double positions lose
/// more than ~1e-12 of its angle: its motions are fitted on the chart's precise offsets.
constexpr double kResolvedExtent = 1e-4;

/// Chart points by chart vertex: the plain positions, and a base (the first point) with offsets
/// from it, the central chart's from the layout's double-double differences.
struct ChartPoints {
  Eigen::MatrixX2d positions;
  Eigen::Vector2d base;
  Eigen::MatrixX2d offsets;
  /// The set's extent over its coordinates' magnitude.
  [[nodiscard]] double relative_extent() const {
    const double extent = offsets.rowwise().norm().maxCoeff();
    const double magnitude = positions.rowwise().norm().maxCoeff();
    return magnitude > 0.0 ? extent / magnitude : 1.0;
  }
  [[nodiscard]] bool resolved() const { return relative_extent() >= kResolvedExtent; }
};

/// Below this relative extent even the double-double offsets (~1e-32 of the magnitude) give an
/// angle worse than the layout's developed directions (~1e-16): side pairings take those.
constexpr double kDirectionExtent = 1e-16;

ChartPoints chart_points(const AffineAtlas& atlas, int chart, const std::vector<int>& ids) {
  const Chart& c = atlas.charts[static_cast<size_t>(chart)];
  ChartPoints p;
  p.positions.resize(static_cast<Eigen::Index>(ids.size()), 2);
  p.offsets.resize(p.positions.rows(), 2);
  for (size_t i = 0; i < ids.size(); ++i)
    p.positions.row(static_cast<Eigen::Index>(i)) = c.positions.row(ids[i]);
  p.base = p.positions.row(0).transpose();
  for (size_t i = 0; i < ids.size(); ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    if (chart == 0) {
      p.offsets.row(row) = atlas.layout.edge_vector(ids[0], ids[i]).transpose();
    } else {
      p.offsets.row(row) = p.positions.row(row) - p.positions.row(0);
    }
  }
  return p;
}

/// The rigid motion taking chart a's vertices `from` to chart b's `to` (paired by index): on
/// the positions where both sets are resolved in doubles, otherwise on the precise offsets (the
/// faces next to a large cone, far smaller than the rounding of their coordinates).
RigidMotion2 fit_points_motion(const ChartPoints& pa, const ChartPoints& pb, double* residual) {
  if (pa.resolved() && pb.resolved()) return fit_rigid_motion(pa.positions, pb.positions, residual);
  return fit_rigid_motion(pa.base, pa.offsets, pb.base, pb.offsets, residual);
}

RigidMotion2 fit_chart_motion(const AffineAtlas& atlas, int a, const std::vector<int>& from,
                              int b, const std::vector<int>& to, double* residual) {
  return fit_points_motion(chart_points(atlas, a, from), chart_points(atlas, b, to), residual);
}

/// One fitted overlap piece: its transition, and whether it was fitted on faces both charts
/// place faithfully (resolved) or on all its faces.
struct FittedPiece {
  Transition transition;
  bool resolved = false;
};

/// Splits the faces shared by charts a and b into pieces glued in both, and fits one rigid
/// motion per piece (reads the atlas only).
std::vector<FittedPiece> fit_pair(const Mesh& mesh, const Eigen::VectorXd& lengths,
                                  const AffineAtlas& atlas, int a, int b,
                                  const std::vector<int>& faces) {
  const Chart& ca = atlas.charts[a];
  const Chart& cb = atlas.charts[b];
  DisjointSets sets(faces.size());
  for (size_t i = 0; i < faces.size(); ++i) {
    const auto hs = face_halfedges(mesh, FaceHandle(faces[i]));
    for (int k = 0; k < 3; ++k) {
      const auto g = mesh.face_handle(mesh.opposite_halfedge_handle(hs[k]));
      if (!g.is_valid()) continue;
      const int j = local_index(faces, g.idx());
      if (j < 0 || !glued(mesh, ca, faces[i], k, g.idx()) ||
          !glued(mesh, cb, faces[i], k, g.idx())) {
        continue;
      }
      sets.unite(static_cast<int>(i), j);
    }
  }
  std::map<int, std::vector<int>> pieces;
  for (size_t i = 0; i < faces.size(); ++i) {
    pieces[sets.find(static_cast<int>(i))].push_back(faces[i]);
  }
  std::vector<FittedPiece> fitted_pieces;
  for (auto& [root, piece] : pieces) {
    std::vector<int> fitted;  // the faces both charts place faithfully, else all
    for (int f : piece) {
      if (places_faithfully(mesh, lengths, ca, ca.slot(f), f) &&
          places_faithfully(mesh, lengths, cb, cb.slot(f), f)) {
        fitted.push_back(f);
      }
    }
    FittedPiece out;
    out.resolved = !fitted.empty();
    if (!out.resolved) fitted = piece;
    std::vector<std::pair<int, int>> pairs;
    for (int f : fitted) {
      for (int k = 0; k < 3; ++k)
        pairs.push_back({ca.corners(ca.slot(f), k), cb.corners(cb.slot(f), k)});
    }
    Transition& t = out.transition;
    t.chart_a = a;
    t.chart_b = b;
    const auto [from, to] = unzip_unique(std::move(pairs));
    t.motion = fit_chart_motion(atlas, a, from, b, to, &t.residual);
    t.faces = std::move(piece);
    fitted_pieces.push_back(std::move(out));
  }
  return fitted_pieces;
}

/// Appends a fitted piece to the atlas' transitions, its faces' lists and the residuals.
void add_piece(FittedPiece piece, AffineAtlas& atlas) {
  const Transition& t = piece.transition;
  const int index = static_cast<int>(atlas.transitions.size());
  for (int f : t.faces) atlas.face_transitions[f].push_back(index);
  if (piece.resolved) {
    atlas.max_transition_residual = std::max(atlas.max_transition_residual, t.residual);
  } else {
    ++atlas.unresolved_transition_pieces;
    atlas.max_unresolved_transition_residual =
        std::max(atlas.max_unresolved_transition_residual, t.residual);
  }
  atlas.transitions.push_back(std::move(piece.transition));
}

/// Arcs of the cut graph: maximal paths whose inner vertices have cut-degree 2 and are neither
/// the root nor on the original boundary.
std::vector<std::vector<HalfedgeHandle>> cut_arcs(const Mesh& mesh, const CutGraph& cut) {
  std::vector<int> degree(mesh.n_vertices(), 0);
  for (auto e : mesh.edges()) {
    if (!cut.is_cut_edge[e.idx()]) continue;
    ++degree[mesh.from_vertex_handle(mesh.halfedge_handle(e, 0)).idx()];
    ++degree[mesh.to_vertex_handle(mesh.halfedge_handle(e, 0)).idx()];
  }
  auto is_node = [&](VertexHandle v) {
    return degree[v.idx()] != 2 || v == cut.root || mesh.is_boundary(v);
  };
  std::vector<char> used(mesh.n_edges(), 0);
  std::vector<std::vector<HalfedgeHandle>> arcs;
  auto walk = [&](HalfedgeHandle h) {
    std::vector<HalfedgeHandle> arc;
    while (true) {
      used[mesh.edge_handle(h).idx()] = 1;
      arc.push_back(h);
      const auto v = mesh.to_vertex_handle(h);
      if (is_node(v)) break;
      HalfedgeHandle next;
      for (auto g : mesh.voh_range(v)) {
        if (cut.is_cut_edge[mesh.edge_handle(g).idx()] && !used[mesh.edge_handle(g).idx()])
          next = g;
      }
      if (!next.is_valid()) break;  // closed arc without node
      h = next;
    }
    arcs.push_back(std::move(arc));
  };
  for (auto v : mesh.vertices()) {
    if (!is_node(v)) continue;
    for (auto h : mesh.voh_range(v)) {
      if (cut.is_cut_edge[mesh.edge_handle(h).idx()] && !used[mesh.edge_handle(h).idx()]) walk(h);
    }
  }
  for (auto e : mesh.edges()) {
    if (cut.is_cut_edge[e.idx()] && !used[e.idx()]) walk(mesh.halfedge_handle(e, 0));
  }
  return arcs;
}

/// The rotation of an arc's side pairing (the copies on its halfedges' faces to the copies
/// across) from the central chart's developed directions: for each arc edge, the direction of
/// its far copy (the opposite halfedge's, turned by pi) minus its near copy's; their circular
/// mean.
double developed_angle(const Mesh& mesh, const SlicedMesh& s, const Eigen::VectorXd& directions,
                       const std::vector<HalfedgeHandle>& arc) {
  double c = 0.0, sn = 0.0;
  for (auto h : arc) {
    const int near = s.from_original_halfedge[h.idx()];
    const int far = s.from_original_halfedge[mesh.opposite_halfedge_handle(h).idx()];
    const double angle = directions[far] + M_PI - directions[near];
    c += std::cos(angle);
    sn += std::sin(angle);
  }
  return std::atan2(sn, c);
}

}  // namespace

void compute_transitions(const Mesh& mesh, const Eigen::VectorXd& lengths, AffineAtlas& atlas) {
  std::vector<std::vector<int>> charts_of_face(mesh.n_faces());
  for (size_t c = 0; c < atlas.charts.size(); ++c) {
    for (int f : atlas.charts[c].faces) charts_of_face[f].push_back(static_cast<int>(c));
  }
  std::map<std::pair<int, int>, std::vector<int>> shared;
  for (auto f : mesh.faces()) {
    const auto& list = charts_of_face[f.idx()];
    for (size_t i = 0; i < list.size(); ++i) {
      for (size_t j = i + 1; j < list.size(); ++j) shared[{list[i], list[j]}].push_back(f.idx());
    }
  }
  atlas.transitions.clear();
  atlas.face_transitions.assign(mesh.n_faces(), {});
  atlas.max_transition_residual = 0.0;
  atlas.unresolved_transition_pieces = 0;
  atlas.max_unresolved_transition_residual = 0.0;
  // Each pair's pieces in a slot of its own, the pairs handed out one at a time (a few pairs
  // of the central chart with the cut-path charts hold most faces), then appended in the map's
  // order: the same transitions in the same order on any number of threads.
  std::vector<const std::pair<const std::pair<int, int>, std::vector<int>>*> pairs;
  pairs.reserve(shared.size());
  for (const auto& entry : shared) pairs.push_back(&entry);
  std::vector<std::vector<FittedPiece>> fitted(pairs.size());
  const int workers = static_cast<int>(
      std::min<std::size_t>(static_cast<std::size_t>(requested_threads(0)), pairs.size()));
  run_blocks_on_demand(workers, pairs.size(), 1, [&](std::size_t i) {
    const auto& [pair, faces] = *pairs[i];
    fitted[i] = fit_pair(mesh, lengths, atlas, pair.first, pair.second, faces);
  });
  for (auto& pieces : fitted) {
    for (FittedPiece& piece : pieces) add_piece(std::move(piece), atlas);
  }
}

void compute_side_pairings(const Mesh& mesh, AffineAtlas& atlas) {
  const SlicedMesh& s = atlas.sliced;
  const Eigen::VectorXd& directions = atlas.layout.halfedge_directions;
  std::vector<int> loop_of_edge(mesh.n_edges(), -1);
  for (size_t i = 0; i < atlas.cut.loops.size(); ++i) {
    loop_of_edge[mesh.edge_handle(atlas.cut.loops[i].generator).idx()] = static_cast<int>(i);
  }
  atlas.side_pairings.clear();
  atlas.max_side_pairing_residual = 0.0;
  for (auto& arc : cut_arcs(mesh, atlas.cut)) {
    std::vector<std::pair<int, int>> pairs;  // (left copy, right copy) of each arc vertex
    SidePairing side;
    for (auto h : arc) {
      const auto o = mesh.opposite_halfedge_handle(h);
      pairs.push_back(
          {s.corner_vertex[mesh.prev_halfedge_handle(h).idx()], s.corner_vertex[o.idx()]});
      pairs.push_back(
          {s.corner_vertex[h.idx()], s.corner_vertex[mesh.prev_halfedge_handle(o).idx()]});
      if (loop_of_edge[mesh.edge_handle(h).idx()] >= 0)
        side.loop = loop_of_edge[mesh.edge_handle(h).idx()];
    }
    const auto [from, to] = unzip_unique(std::move(pairs));
    const ChartPoints pa = chart_points(atlas, 0, from), pb = chart_points(atlas, 0, to);
    if (std::min(pa.relative_extent(), pb.relative_extent()) < kDirectionExtent &&
        directions.size() == static_cast<Eigen::Index>(s.mesh.n_halfedges())) {
      side.motion = fit_rigid_motion(developed_angle(mesh, s, directions, arc), pa.base,
                                     pa.offsets, pb.base, pb.offsets, &side.residual);
    } else {
      side.motion = fit_points_motion(pa, pb, &side.residual);
    }
    side.halfedges = std::move(arc);
    atlas.max_side_pairing_residual = std::max(atlas.max_side_pairing_residual, side.residual);
    atlas.side_pairings.push_back(std::move(side));
  }
}

}  // namespace ricci::detail

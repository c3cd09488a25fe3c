#include "ricci/atlas/atlas.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "ricci/atlas/chart_develop.h"
#include "ricci/atlas/holonomy.h"
#include "ricci/mesh/errors.h"
#include "ricci/util/parallel.h"

namespace ricci {
namespace {

/// Angle at corner `h` (to_vertex(h) in face(h)) from the lengths.
double corner_angle(const Mesh& mesh, const Eigen::VectorXd& lengths, HalfedgeHandle h) {
  return corner_angle_from_lengths(lengths[mesh.edge_handle(mesh.prev_halfedge_handle(h)).idx()],
                                   lengths[mesh.edge_handle(h).idx()],
                                   lengths[mesh.edge_handle(mesh.next_halfedge_handle(h)).idx()]);
}

double vertex_curvature(const Mesh& mesh, const Eigen::VectorXd& lengths, VertexHandle v) {
  double sum = 0.0;
  for (auto h : mesh.vih_range(v)) {
    if (!mesh.is_boundary(h)) sum += corner_angle(mesh, lengths, h);
  }
  return (mesh.is_boundary(v) ? M_PI : 2.0 * M_PI) - sum;
}

Chart central_chart(const Mesh& mesh, const SlicedMesh& sliced, const LayoutE2Result& layout) {
  Chart chart;
  chart.kind = ChartKind::central;
  chart.faces.resize(mesh.n_faces());
  chart.corners.resize(static_cast<Eigen::Index>(mesh.n_faces()), 3);
  for (auto f : mesh.faces()) {
    chart.faces[f.idx()] = f.idx();
    const auto hs = face_halfedges(mesh, f);
    for (int k = 0; k < 3; ++k) chart.corners(f.idx(), k) = sliced.corner_vertex[hs[k].idx()];
  }
  chart.to_original_vertex = sliced.to_original_vertex;
  chart.positions = layout.positions;
  return chart;
}

/// Fills the domain_max_*_length_error fields from the central chart.
void measure_domain_lengths(const Mesh& mesh, const Eigen::VectorXd& lengths, AffineAtlas& atlas) {
  const Chart& central = atlas.charts[0];
  double worst = 0.0, worst_absolute = 0.0;
  for (auto f : mesh.faces()) {
    if (!atlas.in_domain[f.idx()]) continue;
    const auto hs = face_halfedges(mesh, f);
    for (int k = 0; k < 3; ++k) {
      const double l = lengths[mesh.edge_handle(hs[k]).idx()];
      // The layout's double-double differences: the chart's doubles cannot hold edges near a
      // large cone's copies away from the origin.
      const double d = atlas.layout.edge_vector(central.corners(f.idx(), (k + 2) % 3),
                                                central.corners(f.idx(), k))
                           .norm();
      worst = std::max(worst, std::abs(d - l) / l);
      worst_absolute = std::max(worst_absolute, std::abs(d - l));
    }
  }
  atlas.domain_max_relative_length_error = worst;
  atlas.domain_max_absolute_length_error = worst_absolute;
}

/// Vertices of a cut path, in order, with repeats.
std::vector<int> path_vertices(const Mesh& mesh, const CutPath& path) {
  std::vector<int> vertices;
  for (auto h : path.halfedges) {
    vertices.push_back(mesh.from_vertex_handle(h).idx());
    vertices.push_back(mesh.to_vertex_handle(h).idx());
  }
  return vertices;
}

/// A domain face at `vertex` with its central-chart corner positions (the seed of a chart
/// developed in the central chart's frame, so transitions to it start from the identity).
bool seed_at(const Mesh& mesh, const AffineAtlas& atlas, int vertex, int& face,
             Eigen::Matrix<double, 3, 2>& positions) {
  for (auto f : mesh.vf_range(VertexHandle(vertex))) {
    if (!atlas.in_domain[f.idx()]) continue;
    face = f.idx();
    for (int k = 0; k < 3; ++k) {
      positions.row(k) = atlas.charts[0].positions.row(atlas.charts[0].corners(face, k));
    }
    return true;
  }
  return false;
}

void add_cut_path_charts(const Mesh& mesh, const LongLengths& metric, double glue,
                         AffineAtlas& atlas) {
  for (int i = 0; i < atlas.cut_path_count(); ++i) {
    std::vector<int> vertices = path_vertices(mesh, atlas.cut_path(i));
    if (vertices.empty()) continue;
    const int middle = vertices[vertices.size() / 2];
    if (atlas.root_is_cone) {
      vertices.erase(std::remove(vertices.begin(), vertices.end(), atlas.cut.root.idx()),
                     vertices.end());
    }
    int seed = -1;
    Eigen::Matrix<double, 3, 2> seed_positions;
    if (!seed_at(mesh, atlas, middle, seed, seed_positions)) continue;
    const std::vector<int> region = detail::two_ring_faces(mesh, vertices, atlas.in_domain);
    Chart chart = detail::develop_chart(mesh, metric, region, seed, seed_positions, glue);
    chart.kind = ChartKind::cut_path;
    chart.source = i;
    atlas.charts.push_back(std::move(chart));
  }
}

/// Whether `chart` holds every face of `faces` faithfully.
bool holds_faithfully(const Mesh& mesh, const Eigen::VectorXd& lengths, const Chart& chart,
                      const std::vector<int>& faces) {
  for (int f : faces) {
    const int row = chart.slot(f);
    if (row < 0 || !detail::places_faithfully(mesh, lengths, chart, row, f)) return false;
  }
  return true;
}

/// Corner positions of `face` laid out from its lengths in a frame of its own (corner 2 at the
/// origin), for faces the central chart does not place faithfully.
Eigen::Matrix<double, 3, 2> own_frame_positions(const Mesh& mesh, const Eigen::VectorXd& lengths,
                                                int face) {
  const auto hs = face_halfedges(mesh, FaceHandle(face));
  const auto l = [&](int k) { return lengths[mesh.edge_handle(hs[k]).idx()]; };
  Eigen::Matrix<double, 3, 2> p;
  p.row(2) = Eigen::RowVector2d::Zero();
  p.row(0) = Eigen::RowVector2d(l(0), 0.0);
  p.row(1) = place_third_vertex(p.row(2).transpose(), p.row(0).transpose(), l(2), l(1)).transpose();
  return p;
}

/// Develops exactly `hood` (the neighbourhood of `face`) as a chart of its own; returns its
/// index, or -1 (and adds nothing) when even the neighbourhood is not one planar piece (it
/// wraps around a handle). The seed is the central chart's placement when the chart developed
/// from it holds the hood faithfully (transitions near the identity), else the face in its own
/// frame, with copies glued within `glue_tolerance` of the neighbourhood's mean edge.
int add_face_chart(const Mesh& mesh, const Eigen::VectorXd& lengths, const LongLengths& metric,
                   double glue, double glue_tolerance, int face, const std::vector<int>& hood,
                   AffineAtlas& atlas) {
  Eigen::Matrix<double, 3, 2> seed_positions;
  for (int k = 0; k < 3; ++k) {
    seed_positions.row(k) = atlas.charts[0].positions.row(atlas.charts[0].corners(face, k));
  }
  Chart chart = detail::develop_chart(mesh, metric, hood, face, seed_positions, glue);
  if (!holds_faithfully(mesh, lengths, chart, hood)) {
    double sum = 0.0;
    int count = 0;
    for (int g : hood) {
      for (auto e : mesh.fe_range(FaceHandle(g))) {
        sum += lengths[e.idx()];
        ++count;
      }
    }
    const double local_glue = std::min(glue, glue_tolerance * sum / std::max(count, 1));
    chart = detail::develop_chart(mesh, metric, hood, face,
                                  own_frame_positions(mesh, lengths, face), local_glue);
  }
  if (!detail::holds_as_one_piece(mesh, chart, hood)) return -1;
  chart.kind = ChartKind::face;
  chart.source = face;
  atlas.charts.push_back(std::move(chart));
  return static_cast<int>(atlas.charts.size()) - 1;
}

/// Whether `chart` holds `hood` as one piece and faithfully.
bool fits_neighbourhood(const Mesh& mesh, const Eigen::VectorXd& lengths, const Chart& chart,
                        const std::vector<int>& hood) {
  return detail::holds_as_one_piece(mesh, chart, hood) &&
         holds_faithfully(mesh, lengths, chart, hood);
}

/// For every domain face, whether the central chart (atlas.charts[0]) holds its neighbourhood
/// as one piece and faithfully; face-parallel, each face its own slot (the same answers on any
/// number of threads). Away from the cut the central chart holds a neighbourhood whose faces
/// it holds faithfully and whose vertices it has once each: that test is per vertex (a face's
/// neighbourhood is its vertices' domain stars), so only the faces failing it gather their
/// neighbourhood for holds_as_one_piece's search and sort.
std::vector<char> central_chart_serves(const Mesh& mesh, const Eigen::VectorXd& lengths,
                                       const AffineAtlas& atlas) {
  const Chart& central = atlas.charts[0];
  std::vector<char> in_central(mesh.n_faces(), 0), copies(mesh.n_vertices(), 0);
  parallel_for(central.faces.size(), 0, [&](size_t i) {
    const int f = central.faces[i];
    in_central[static_cast<size_t>(f)] = detail::places_faithfully(mesh, lengths, central, f, f);
  });
  for (int v : central.to_original_vertex) {
    char& count = copies[static_cast<size_t>(v)];
    count = static_cast<char>(std::min(count + 1, 2));
  }
  // Whether every domain face around v is faithful in the central chart with each of its
  // vertices there once (vacuously true without domain faces, as an empty neighbourhood is).
  std::vector<char> plain(mesh.n_vertices(), 0);
  parallel_for(mesh.n_vertices(), 0, [&](size_t v) {
    for (auto g : mesh.vf_range(VertexHandle(static_cast<int>(v)))) {
      if (!atlas.in_domain[static_cast<size_t>(g.idx())]) continue;
      if (!in_central[static_cast<size_t>(g.idx())]) return;
      for (auto w : mesh.fv_range(g)) {
        if (copies[static_cast<size_t>(w.idx())] != 1) return;
      }
    }
    plain[v] = 1;
  });
  std::vector<char> serves(mesh.n_faces(), 0);
  parallel_for(mesh.n_faces(), 0, [&](size_t f) {
    if (!atlas.in_domain[f]) return;
    bool plainly_central = true;
    for (auto v : mesh.fv_range(FaceHandle(static_cast<int>(f)))) {
      if (!plain[static_cast<size_t>(v.idx())]) plainly_central = false;
    }
    if (plainly_central) {
      serves[f] = 1;
      return;
    }
    const std::vector<int> hood =
        detail::face_neighbourhood(mesh, static_cast<int>(f), atlas.in_domain);
    serves[f] = fits_neighbourhood(mesh, lengths, central, hood) ? 1 : 0;
  });
  return serves;
}

/// Picks, for every domain face, the first chart holding its neighbourhood as one piece and
/// faithfully (places_faithfully): central, then cut-path charts holding the face, then (built
/// on demand) vertex charts, then a chart of the face's own neighbourhood.
void assign_neighbourhood_charts(const Mesh& mesh, const Eigen::VectorXd& lengths,
                                 const LongLengths& metric, double glue, double glue_tolerance,
                                 AffineAtlas& atlas) {
  std::vector<std::vector<int>> charts_of_face(mesh.n_faces());
  for (size_t c = 1; c < atlas.charts.size(); ++c) {
    for (int f : atlas.charts[c].faces) charts_of_face[f].push_back(static_cast<int>(c));
  }
  std::map<int, int> vertex_chart;  // original vertex -> chart index (-1: none possible)
  atlas.neighbourhood_chart.assign(mesh.n_faces(), -1);
  atlas.uncovered_faces = 0;
  const std::vector<char> central_serves = central_chart_serves(mesh, lengths, atlas);
  // (atlas.charts grows below: no reference into it is kept.)
  for (auto f : mesh.faces()) {
    if (!atlas.in_domain[f.idx()]) continue;
    if (central_serves[static_cast<size_t>(f.idx())]) {
      atlas.neighbourhood_chart[f.idx()] = 0;
      continue;
    }
    const std::vector<int> hood = detail::face_neighbourhood(mesh, f.idx(), atlas.in_domain);
    const auto fits = [&](int c) {
      return fits_neighbourhood(mesh, lengths, atlas.charts[static_cast<size_t>(c)], hood);
    };
    int found = -1;
    for (size_t i = 0; found < 0 && i < charts_of_face[f.idx()].size(); ++i) {
      const int c = charts_of_face[f.idx()][i];
      if (fits(c)) found = c;
    }
    for (auto v : mesh.fv_range(f)) {
      if (found >= 0) break;
      auto it = vertex_chart.find(v.idx());
      if (it == vertex_chart.end()) {
        int seed = -1;
        Eigen::Matrix<double, 3, 2> seed_positions;
        int index = -1;
        if (seed_at(mesh, atlas, v.idx(), seed, seed_positions)) {
          const auto region = detail::two_ring_faces(mesh, {v.idx()}, atlas.in_domain);
          Chart chart = detail::develop_chart(mesh, metric, region, seed, seed_positions, glue);
          chart.kind = ChartKind::vertex;
          chart.source = v.idx();
          index = static_cast<int>(atlas.charts.size());
          atlas.charts.push_back(std::move(chart));
        }
        it = vertex_chart.emplace(v.idx(), index).first;
      }
      if (it->second >= 0 && fits(it->second)) found = it->second;
    }
    if (found < 0)
      found = add_face_chart(mesh, lengths, metric, glue, glue_tolerance, f.idx(), hood, atlas);
    atlas.neighbourhood_chart[f.idx()] = found;
    if (found < 0) ++atlas.uncovered_faces;
  }
}

}  // namespace

int Chart::slot(int face) const {
  const auto it = std::lower_bound(faces.begin(), faces.end(), face);
  return it != faces.end() && *it == face ? static_cast<int>(it - faces.begin()) : -1;
}

int AffineAtlas::cut_path_count() const {
  return static_cast<int>(cut.loops.size() + cut.boundary_connectors.size());
}

const CutPath& AffineAtlas::cut_path(int index) const {
  const int loops = static_cast<int>(cut.loops.size());
  return index < loops ? cut.loops[index] : cut.boundary_connectors[index - loops];
}

Eigen::Vector2d AffineAtlas::corner_position(int chart, int face, int corner) const {
  if (chart < 0 || chart >= static_cast<int>(charts.size())) {
    throw InvalidInputError("atlas: chart " + std::to_string(chart) + " does not exist");
  }
  const Chart& c = charts[chart];
  const int row = c.slot(face);
  if (row < 0 || corner < 0 || corner > 2) {
    throw InvalidInputError("atlas: chart " + std::to_string(chart) + " does not hold face " +
                            std::to_string(face) + " corner " + std::to_string(corner));
  }
  return c.positions.row(c.corners(row, corner)).transpose();
}

Eigen::Matrix<double, 3, 2> AffineAtlas::face_positions(int chart, int face) const {
  Eigen::Matrix<double, 3, 2> p;
  for (int k = 0; k < 3; ++k) p.row(k) = corner_position(chart, face, k).transpose();
  return p;
}

std::optional<RigidMotion2> AffineAtlas::transition(int chart_a, int chart_b, int face) const {
  if (chart_a == chart_b) return RigidMotion2{};
  if (face < 0 || face >= static_cast<int>(face_transitions.size())) return std::nullopt;
  for (int t : face_transitions[face]) {
    const Transition& tr = transitions[t];
    if (tr.chart_a == chart_a && tr.chart_b == chart_b) return tr.motion;
    if (tr.chart_a == chart_b && tr.chart_b == chart_a) return tr.motion.inverse();
  }
  return std::nullopt;
}

Eigen::Vector2d AffineAtlas::map(const Eigen::Vector2d& point, int chart_a, int chart_b,
                                 int face) const {
  const auto motion = transition(chart_a, chart_b, face);
  if (!motion) {
    throw InvalidInputError("atlas: charts " + std::to_string(chart_a) + " and " +
                            std::to_string(chart_b) + " do not overlap at face " +
                            std::to_string(face));
  }
  return motion->apply(point);
}

AffineAtlas build_affine_atlas(const Mesh& mesh, const Eigen::VectorXd& edge_lengths,
                               VertexHandle root, const AtlasOptions& options) {
  return build_affine_atlas(mesh, edge_lengths, Eigen::VectorXd(), root, options);
}

AffineAtlas build_affine_atlas(const Mesh& mesh, const Eigen::VectorXd& edge_lengths,
                               const Eigen::VectorXd& lengths_low, VertexHandle root,
                               const AtlasOptions& options) {
  AffineAtlas atlas;
  atlas.cut = compute_cut_graph(mesh, root, edge_lengths);
  atlas.sliced = slice_along(mesh, atlas.cut.is_cut_edge);
  complete_affine_atlas(mesh, edge_lengths, lengths_low, options, atlas);
  return atlas;
}

void complete_affine_atlas(const Mesh& mesh, const Eigen::VectorXd& edge_lengths,
                           const Eigen::VectorXd& lengths_low, const AtlasOptions& options,
                           AffineAtlas& atlas) {
  const VertexHandle root = atlas.cut.root;
  if (atlas.cut.is_cut_edge.size() != mesh.n_edges() ||
      atlas.sliced.mesh.n_faces() != mesh.n_faces() || !root.is_valid() ||
      root.idx() >= static_cast<int>(mesh.n_vertices())) {
    throw InvalidInputError("atlas: the cut graph or the slicing was not made from this mesh");
  }
  const Eigen::VectorXd lengths = checked_edge_lengths(mesh, edge_lengths);
  // The paths' lengths in this metric (compute_cut_graph's sums, in the same order).
  for (auto* paths : {&atlas.cut.loops, &atlas.cut.boundary_connectors}) {
    for (CutPath& path : *paths) {
      path.length = 0.0;
      for (auto h : path.halfedges) path.length += lengths[mesh.edge_handle(h).idx()];
    }
  }
  const LongLengths metric = long_lengths(lengths, lengths_low);
  check_disk(atlas.sliced, "atlas");
  atlas.polygon = fundamental_polygon_word(mesh, atlas.cut, atlas.sliced);
  atlas.layout = layout_e2(
      atlas.sliced.mesh, sliced_edge_lengths(atlas.sliced, lengths),
      lengths_low.size() == 0 ? Eigen::VectorXd() : sliced_edge_lengths(atlas.sliced, lengths_low),
      options.layout);

  atlas.root_curvature = vertex_curvature(mesh, lengths, root);
  atlas.root_is_cone =
      !mesh.is_boundary(root) && std::abs(atlas.root_curvature) > options.cone_tolerance;
  atlas.in_domain.assign(mesh.n_faces(), 1);
  if (atlas.root_is_cone) {
    for (auto f : mesh.vf_range(root)) atlas.in_domain[f.idx()] = 0;
  }
  atlas.charts.push_back(central_chart(mesh, atlas.sliced, atlas.layout));
  measure_domain_lengths(mesh, lengths, atlas);
  const Eigen::Vector2d lo = atlas.layout.positions.colwise().minCoeff();
  const Eigen::Vector2d hi = atlas.layout.positions.colwise().maxCoeff();
  atlas.domain_diameter = (hi - lo).norm();

  const double glue = options.glue_tolerance * lengths.mean();
  add_cut_path_charts(mesh, metric, glue, atlas);
  assign_neighbourhood_charts(mesh, lengths, metric, glue, options.glue_tolerance, atlas);
  detail::compute_transitions(mesh, lengths, atlas);
  detail::compute_side_pairings(mesh, atlas);
  atlas.canonical = canonical_basis(atlas.polygon.word);
  atlas.loop_holonomy = loop_holonomies(mesh, atlas);
  if (!atlas.loop_holonomy.empty()) {
    for (const auto& generator : atlas.canonical.generators) {
      atlas.canonical_holonomy.push_back(word_holonomy(atlas.loop_holonomy, generator));
    }
    const RigidMotion2 relator = word_holonomy(atlas.loop_holonomy, atlas.polygon.word);
    atlas.relator_holonomy_angle = std::abs(relator.angle);
    atlas.relator_holonomy_translation = relator.translation.norm();
  }
}

}  // namespace ricci

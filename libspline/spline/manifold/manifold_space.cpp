#include "spline/manifold/manifold_space.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>

#include "ricci/atlas/rigid_motion.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/primitives.h"
#include "ricci/topology/slice.h"
#include "ricci/util/cross2d.h"

namespace spline {
namespace {

using ricci::InvalidInputError;
using ricci::TopologyError;

std::string face_name(int face) { return "face " + std::to_string(face); }

// Around a cone of 2 pi (2g - 1) the flat metric shrinks like rho^(2g - 2): at genus 8 faces of
// the refined one-ring are 1e-13 of the central chart's coordinates. The atlas gives such faces
// neighbourhood charts in their own frame (ricci/atlas/atlas.cpp, places_faithfully); a face
// still below kMinChartInradius times its neighbourhood chart's coordinates carries no functions
// (from genus kSizeRulesGenus: at genus 0 the one-cone metric shrinks long extremities far more
// than a cone does, camel.off's legs, and such faces were fitted well without the rule).
constexpr double kMinChartInradius = 1e-13;
constexpr double kMinRelativeInradius = 1e-8;
constexpr int kSizeRulesGenus = 4;
// Below this genus the stricter rules always apply (apply_strict_rules): generated genus 6 with
// the faces next to its cone kept came out with spikes (6-8% of the diagonal from the input,
// not traced), with them left out at a seam of 0.2 degrees.
constexpr int kFaithfulRulesGenus = 8;
// A chart other than a face's neighbourhood chart carries the face's functions only when it
// places the face as that chart does (edge lengths within this relative accuracy,
// counter-clockwise): the central chart's rounding breaks the faces next to a large cone. (The
// atlas places each neighbourhood within 1e-9 of the metric, so two such charts agree within
// 2e-9.)
constexpr double kSameShape = 1e-8;
// Knot clouds move between charts by the atlas transition only when it places the vertex
// within this fraction of the face's shortest edge (and 1e-7 of the domain diameter).
constexpr double kTransitionToEdge = 1e-6;

// Corner of chart row `row` at original vertex v, or -1.
int corner_at(const ricci::Chart& chart, int row, int vertex) {
  for (int k = 0; k < 3; ++k) {
    if (chart.to_original_vertex[chart.corners(row, k)] == vertex) return k;
  }
  return -1;
}

// A given home cloud (ManifoldSplineSpace's second constructor): n + 1 finite knots starting
// exactly at the vertex, the others closer to it than half the smallest inradius of its
// triangles (the bound under which knot_cloud.h guarantees the DMS conditions).
void check_home_cloud(const KnotCloud& cloud, int vertex, int degree,
                      const Eigen::Vector2d& center, const std::vector<Eigen::Vector2d>& ring,
                      bool closed) {
  const std::string where = "manifold spline: home cloud of vertex " + std::to_string(vertex);
  if (cloud.degree() != degree) {
    throw InvalidInputError(where + " has " + std::to_string(cloud.knots.size()) +
                            " knots, degree " + std::to_string(degree) + " needs " +
                            std::to_string(degree + 1));
  }
  if (cloud.knots[0] != center) {
    throw InvalidInputError(where + " does not start at the vertex's home-chart position");
  }
  const std::size_t fan = closed ? ring.size() : ring.size() - 1;
  double smallest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < fan; ++i) {
    smallest = std::min(smallest, inradius(center, ring[i], ring[(i + 1) % ring.size()]));
  }
  for (const Eigen::Vector2d& knot : cloud.knots) {
    if (!knot.allFinite() || !((knot - center).norm() < 0.5 * smallest)) {
      throw InvalidInputError(where + " has a knot " +
                              (knot.allFinite() ? "farther than half the smallest inradius"
                                                : "that is not finite"));
    }
  }
}

// The stricter rules of a face's usability (from genus kSizeRulesGenus): counter-clockwise in
// every chart holding it, an inradius above kMinChartInradius of the coordinates in each, and
// above kMinRelativeInradius of the median face's smallest chart inradius. Where the faces they
// leave out form disks, the hole's patch replaces them (generated genus 4 and 6: seams of 0.3
// and 0.2 degrees); next to a cone of genus 8 they form a pair of pants round two tubes, which
// disks cannot close (the surface came out of genus 6), and the faithful rules alone apply.
void apply_strict_rules(const ricci::AffineAtlas& atlas, std::vector<char>& usable) {
  std::vector<double> smallest(usable.size(), INFINITY);
  for (const ricci::Chart& chart : atlas.charts) {
    for (std::size_t row = 0; row < chart.faces.size(); ++row) {
      const auto r = static_cast<Eigen::Index>(row);
      const int face = chart.faces[row];
      const Eigen::Vector2d a = chart.positions.row(chart.corners(r, 0)).transpose();
      const Eigen::Vector2d b = chart.positions.row(chart.corners(r, 1)).transpose();
      const Eigen::Vector2d c = chart.positions.row(chart.corners(r, 2)).transpose();
      const double rho = ricci::cross2d(b - a, c - a) > 0.0 ? inradius(a, b, c) : 0.0;
      if (!(rho > kMinChartInradius * std::max({a.norm(), b.norm(), c.norm()}))) usable[face] = 0;
      smallest[face] = std::min(smallest[face], rho);
    }
  }
  std::vector<double> inradii;
  for (std::size_t i = 0; i < usable.size(); ++i) {
    if (atlas.in_domain[i] && std::isfinite(smallest[i])) inradii.push_back(smallest[i]);
  }
  if (inradii.empty()) return;
  const auto middle = inradii.begin() + static_cast<std::ptrdiff_t>(inradii.size() / 2);
  std::nth_element(inradii.begin(), middle, inradii.end());
  for (std::size_t i = 0; i < usable.size(); ++i) {
    if (!(smallest[i] >= kMinRelativeInradius * *middle)) usable[i] = 0;
  }
}

// Edge-connected pieces of the faces with inside[f] == want: a piece index by face (-1 for the
// others) and the piece count.
int face_pieces(const ricci::Mesh& mesh, const std::vector<char>& inside, char want,
                std::vector<int>& piece) {
  piece.assign(mesh.n_faces(), -1);
  int count = 0;
  for (auto start : mesh.faces()) {
    if (inside[start.idx()] != want || piece[start.idx()] >= 0) continue;
    std::vector<int> stack{start.idx()};
    piece[start.idx()] = count;
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      for (auto g : mesh.ff_range(mesh.face_handle(f))) {
        if (inside[g.idx()] == want && piece[g.idx()] < 0) {
          piece[g.idx()] = count;
          stack.push_back(g.idx());
        }
      }
    }
    ++count;
  }
  return count;
}

// Whether the faces outside `kept`, with the islands of kept faces they enclose (every kept
// piece but the largest, which find_rims covers too), form disks: each edge-connected piece has
// Euler characteristic 1 (V - E + F of the closed faces; pieces meeting at a vertex fail).
bool holes_are_disks(const ricci::Mesh& mesh, std::vector<char> kept) {
  std::vector<int> piece;
  const int kept_pieces = face_pieces(mesh, kept, 1, piece);
  if (kept_pieces > 1) {
    std::vector<int> size(static_cast<std::size_t>(kept_pieces), 0);
    for (int p : piece) {
      if (p >= 0) ++size[static_cast<std::size_t>(p)];
    }
    const auto largest =
        static_cast<int>(std::max_element(size.begin(), size.end()) - size.begin());
    for (std::size_t f = 0; f < kept.size(); ++f) {
      if (piece[f] >= 0 && piece[f] != largest) kept[f] = 0;
    }
  }
  std::vector<int> hole;
  for (auto f : mesh.faces()) {
    if (!kept[f.idx()]) hole.push_back(f.idx());
  }
  if (hole.empty()) return true;
  std::vector<char> vertex(mesh.n_vertices(), 0), edge(mesh.n_edges(), 0);
  long euler = static_cast<long>(hole.size());
  for (int f : hole) {
    for (auto v : mesh.fv_range(mesh.face_handle(f))) euler += vertex[v.idx()]++ == 0 ? 1 : 0;
    for (auto e : mesh.fe_range(mesh.face_handle(f))) euler -= edge[e.idx()]++ == 0 ? 1 : 0;
  }
  const long count = face_pieces(mesh, kept, 0, piece);
  return euler == count;
}

}  // namespace

ManifoldSplineSpace::~ManifoldSplineSpace() = default;

ManifoldSplineSpace::ManifoldSplineSpace(const ricci::Mesh& mesh, const ricci::AffineAtlas& atlas,
                                         const ManifoldSplineOptions& options)
    : degree_(options.degree), atlas_(atlas) {
  build_domain(mesh);
  build_home_clouds(mesh, options, nullptr);
  chart_spaces_.resize(atlas_.charts.size());
  chart_once_ = std::make_unique<std::once_flag[]>(atlas_.charts.size());
}

ManifoldSplineSpace::ManifoldSplineSpace(const ricci::Mesh& mesh, const ricci::AffineAtlas& atlas,
                                         int degree, std::vector<KnotCloud> home_clouds)
    : degree_(degree), atlas_(atlas) {
  build_domain(mesh);
  ManifoldSplineOptions options;
  options.degree = degree;
  build_home_clouds(mesh, options, &home_clouds);
  chart_spaces_.resize(atlas_.charts.size());
  chart_once_ = std::make_unique<std::once_flag[]>(atlas_.charts.size());
}

void ManifoldSplineSpace::build_domain(const ricci::Mesh& mesh) {
  if (degree_ < 1 || degree_ > kMaxDmsDegree) {
    throw InvalidInputError("manifold spline: degree " + std::to_string(degree_) + " outside 1.." +
                            std::to_string(kMaxDmsDegree));
  }
  const int faces = static_cast<int>(mesh.n_faces());
  if (static_cast<int>(atlas_.in_domain.size()) != faces ||
      static_cast<int>(atlas_.neighbourhood_chart.size()) != faces) {
    throw InvalidInputError("manifold spline: the atlas has " +
                            std::to_string(atlas_.in_domain.size()) + " faces, the mesh " +
                            std::to_string(faces));
  }
  // A face without a neighbourhood chart (atlas.uncovered_faces), not strictly counter-clockwise
  // there (a flipped sliver), or too small there for its knots to be told apart in the chart's
  // coordinates (kMinChartInradius) cannot carry DMS functions: it joins the hole.
  std::vector<char> usable(static_cast<std::size_t>(faces), 0);
  const int genus = ricci::surface_topology(mesh).genus;
  const bool size_rules = genus >= kSizeRulesGenus;
  for (int i = 0; i < faces; ++i) {
    const int c = atlas_.neighbourhood_chart[i];
    if (c < 0) continue;
    const Eigen::Matrix<double, 3, 2> p = atlas_.face_positions(c, i);
    const Eigen::Vector2d a = p.row(0).transpose(), b = p.row(1).transpose(),
                          d = p.row(2).transpose();
    if (!(ricci::cross2d(b - a, d - a) > 0.0)) continue;
    usable[i] = !size_rules ||
                inradius(a, b, d) > kMinChartInradius * std::max({a.norm(), b.norm(), d.norm()});
  }
  if (size_rules) {
    std::vector<char> strict = usable;
    apply_strict_rules(atlas_, strict);
    for (int i = 0; i < faces; ++i) strict[i] = strict[i] && atlas_.in_domain[i];
    if (genus < kFaithfulRulesGenus || holes_are_disks(mesh, strict)) usable = std::move(strict);
  }
  domain_index_.assign(static_cast<std::size_t>(faces), -1);
  neighbours_.assign(static_cast<std::size_t>(faces), {-1, -1, -1});
  vertex_faces_.assign(mesh.n_vertices(), {});
  for (auto f : mesh.faces()) {
    const int i = f.idx();
    const auto hs = ricci::face_halfedges(mesh, f);
    // Edge opposite corner k runs from corner k+1 to corner k+2: halfedge k+2.
    for (int k = 0; k < 3; ++k) {
      const auto opposite = mesh.opposite_halfedge_handle(hs[(k + 2) % 3]);
      const auto g = mesh.face_handle(opposite);
      neighbours_[i][k] = g.is_valid() ? g.idx() : -1;
    }
    if (!atlas_.in_domain[i]) continue;
    if (!usable[i]) {
      ++excluded_faces_;
      continue;
    }
    domain_index_[i] = static_cast<int>(domain_faces_.size());
    domain_faces_.push_back(i);
    for (int k = 0; k < 3; ++k) vertex_faces_[mesh.to_vertex_handle(hs[k]).idx()].push_back(i);
  }
  // Points are evaluated in their face's neighbourhood chart: its corners there and its row
  // once, not by a search of the chart's faces per point.
  home_corners_.assign(static_cast<std::size_t>(faces), Eigen::Matrix<double, 3, 2>::Zero());
  home_row_.assign(static_cast<std::size_t>(faces), -1);
  for (int i : domain_faces_) {
    const int c = atlas_.neighbourhood_chart[i];
    home_corners_[i] = atlas_.face_positions(c, i);
    home_row_[i] = atlas_.charts[c].slot(i);
  }
}

// Home cloud of v: made in the neighbourhood chart of v's lowest domain face, which holds v's
// whole domain star glued around one copy of v (the atlas guarantees this per face).
void ManifoldSplineSpace::build_home_clouds(const ricci::Mesh& mesh,
                                            const ManifoldSplineOptions& options,
                                            std::vector<KnotCloud>* given) {
  const std::size_t n_vertices = mesh.n_vertices();
  if (given && given->size() != n_vertices) {
    throw InvalidInputError("manifold spline: " + std::to_string(given->size()) +
                            " home clouds for " + std::to_string(n_vertices) + " vertices");
  }
  home_clouds_.assign(n_vertices, {});
  home_chart_.assign(n_vertices, -1);
  home_face_.assign(n_vertices, -1);
  for (std::size_t v = 0; v < n_vertices; ++v) {
    const auto& star = vertex_faces_[v];
    if (star.empty()) {
      if (given && !(*given)[v].knots.empty()) {
        throw InvalidInputError("manifold spline: vertex " + std::to_string(v) +
                                " is in no domain face but has a home cloud");
      }
      continue;
    }
    const int vertex = static_cast<int>(v);
    const int home_face = *std::min_element(star.begin(), star.end());
    const int chart_index = atlas_.neighbourhood_chart[home_face];
    if (chart_index < 0) {
      throw TopologyError("manifold spline: " + face_name(home_face) +
                          " has no neighbourhood chart (vertex " + std::to_string(vertex) + ")");
    }
    const ricci::Chart& chart = atlas_.charts[chart_index];
    int copy = -1;
    std::map<int, int> next;  // ring neighbour a -> b for each ccw triangle (v, a, b)
    for (int f : star) {
      const int row = chart.slot(f);
      const int k = row < 0 ? -1 : corner_at(chart, row, vertex);
      if (k < 0 || (copy >= 0 && chart.corners(row, k) != copy)) {
        throw TopologyError("manifold spline: chart " + std::to_string(chart_index) +
                            " does not hold the star of vertex " + std::to_string(vertex) +
                            " glued (" + face_name(f) + ")");
      }
      copy = chart.corners(row, k);
      next[chart.corners(row, (k + 1) % 3)] = chart.corners(row, (k + 2) % 3);
    }
    // An open fan (hole or surface boundary) starts at the neighbour no triangle ends at.
    int start = next.begin()->first;
    std::vector<int> targets;
    for (const auto& entry : next) targets.push_back(entry.second);
    for (const auto& entry : next) {
      if (std::find(targets.begin(), targets.end(), entry.first) == targets.end())
        start = entry.first;
    }
    std::vector<Eigen::Vector2d> ring{chart.positions.row(start).transpose()};
    int current = start;
    bool closed = false;
    for (std::size_t step = 0; step < next.size(); ++step) {
      const auto it = next.find(current);
      if (it == next.end()) break;
      current = it->second;
      if (current == start) {
        closed = true;
        break;
      }
      ring.push_back(chart.positions.row(current).transpose());
    }
    home_chart_[v] = chart_index;
    home_face_[v] = home_face;
    const Eigen::Vector2d center = chart.positions.row(copy).transpose();
    if (given) {
      check_home_cloud((*given)[v], vertex, degree_, center, ring, closed);
      home_clouds_[v] = std::move((*given)[v]);
    } else {
      home_clouds_[v] = make_knot_cloud(degree_, static_cast<std::uint64_t>(vertex), center, ring,
                                        closed, options.knots);
    }
  }
}

// The home cloud of corner k of `face` moved into `chart`: by the atlas transition around `face`
// when it places the vertex where the chart has it, else by the rigid motion of the face's own
// corners (same chart, another copy; or charts without a recorded transition).
KnotCloud ManifoldSplineSpace::cloud_in_chart(int chart, int face, int corner) const {
  const ricci::Chart& target = atlas_.charts[chart];
  const int row = target.slot(face);
  const int copy = target.corners(row, corner);
  const int vertex = target.to_original_vertex[copy];
  const int home = home_chart_[vertex];
  const ricci::Chart& source = atlas_.charts[home];
  const int home_row = source.slot(face);
  const Eigen::Vector2d here = target.positions.row(copy).transpose();
  const Eigen::Vector2d there = source.positions.row(source.corners(home_row, corner)).transpose();
  std::optional<ricci::RigidMotion2> motion;
  if (home != chart) motion = atlas_.transition(home, chart, face);
  const Eigen::Matrix<double, 3, 2> p = atlas_.face_positions(chart, face);
  const double shortest = std::min(
      {(p.row(0) - p.row(1)).norm(), (p.row(1) - p.row(2)).norm(), (p.row(2) - p.row(0)).norm()});
  const double tolerance =
      std::min(1e-7 * std::max(atlas_.domain_diameter, 1e-300), kTransitionToEdge * shortest);
  // (A transition fitted over vertices the layout lost, non-finite next to a genus-9 cone,
  // fails this test too.)
  if (!motion || !((motion->apply(there) - here).norm() <= tolerance)) {
    motion = ricci::fit_rigid_motion(atlas_.face_positions(home, face),
                                     atlas_.face_positions(chart, face));
  }
  KnotCloud cloud = transformed(home_clouds_[vertex], motion->rotation(), motion->translation);
  cloud.knots[0] = here;  // exact: PlanarDmsSpace requires knots[0] == the vertex
  return cloud;
}

bool ManifoldSplineSpace::same_shape_as_home(int chart, int face) const {
  const int home = atlas_.neighbourhood_chart[face];
  if (home == chart) return true;
  const Eigen::Matrix<double, 3, 2> p = atlas_.face_positions(chart, face);
  const Eigen::Matrix<double, 3, 2> q = atlas_.face_positions(home, face);
  for (int k = 0; k < 3; ++k) {
    const double there = (q.row(k) - q.row((k + 1) % 3)).norm();
    const double here = (p.row(k) - p.row((k + 1) % 3)).norm();
    if (!(std::abs(here - there) <= kSameShape * there)) return false;
  }
  return ricci::cross2d((p.row(1) - p.row(0)).transpose(), (p.row(2) - p.row(0)).transpose()) > 0.0;
}

std::unique_ptr<ManifoldSplineSpace::ChartSpace> ManifoldSplineSpace::build_chart_space(
    int chart_index) const {
  const ricci::Chart& chart = atlas_.charts[chart_index];
  auto result = std::make_unique<ChartSpace>();
  result->triangle_of_row.assign(chart.faces.size(), -1);
  std::vector<int> local(static_cast<std::size_t>(chart.positions.rows()), -1);
  PlanarTriangulation triangulation;
  std::vector<KnotCloud> clouds;
  for (std::size_t row = 0; row < chart.faces.size(); ++row) {
    const int face = chart.faces[row];
    if (domain_index_[face] < 0 || !same_shape_as_home(chart_index, face)) continue;
    Eigen::Vector3i triangle;
    for (int k = 0; k < 3; ++k) {
      const int copy = chart.corners(static_cast<Eigen::Index>(row), k);
      if (local[copy] < 0) {
        local[copy] = static_cast<int>(triangulation.positions.size());
        triangulation.positions.push_back(chart.positions.row(copy).transpose());
        clouds.push_back(cloud_in_chart(chart_index, face, k));
      }
      triangle[k] = local[copy];
    }
    result->triangle_of_row[row] = static_cast<int>(triangulation.triangles.size());
    result->face_of_triangle.push_back(face);
    triangulation.triangles.push_back(triangle);
  }
  result->triangles_at_vertex.resize(triangulation.positions.size());
  for (std::size_t t = 0; t < triangulation.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k)
      result->triangles_at_vertex[triangulation.triangles[t][k]].push_back(static_cast<int>(t));
  }
  result->around_start.push_back(0);
  std::vector<int> around;
  for (const Eigen::Vector3i& own : triangulation.triangles) {
    around.clear();
    for (int k = 0; k < 3; ++k) {
      const auto& star = result->triangles_at_vertex[own[k]];
      around.insert(around.end(), star.begin(), star.end());
    }
    std::sort(around.begin(), around.end());
    around.erase(std::unique(around.begin(), around.end()), around.end());
    result->around.insert(result->around.end(), around.begin(), around.end());
    result->around_start.push_back(static_cast<int>(result->around.size()));
  }
  // A chart made only of hole faces has no space (nothing is evaluated there).
  if (!triangulation.triangles.empty()) {
    result->space = std::make_unique<PlanarDmsSpace>(std::move(triangulation), std::move(clouds));
  }
  return result;
}

const ManifoldSplineSpace::ChartSpace& ManifoldSplineSpace::chart_space(int chart) const {
  if (chart < 0 || chart >= static_cast<int>(chart_spaces_.size())) {
    throw InvalidInputError("manifold spline: chart " + std::to_string(chart) + " does not exist");
  }
  std::call_once(chart_once_[chart], [&] { chart_spaces_[chart] = build_chart_space(chart); });
  return *chart_spaces_[chart];
}

bool ManifoldSplineSpace::holds_neighbourhood(int chart_index, int face) const {
  const ricci::Chart& chart = atlas_.charts[chart_index];
  const int row = chart.slot(face);
  if (row < 0 || domain_index_[face] < 0) return false;
  for (int k = 0; k < 3; ++k) {
    const int copy = chart.corners(row, k);
    const int vertex = chart.to_original_vertex[copy];
    for (int g : vertex_faces_[vertex]) {
      const int g_row = chart.slot(g);
      if (g_row < 0) return false;
      const int corner = corner_at(chart, g_row, vertex);
      if (corner < 0 || chart.corners(g_row, corner) != copy) return false;
      if (!same_shape_as_home(chart_index, g)) return false;
    }
  }
  return true;
}

Eigen::Vector2d ManifoldSplineSpace::chart_point(int chart, int face,
                                                 const Eigen::Vector3d& bary) const {
  if (is_home(chart, face)) return home_corners_[face].transpose() * bary;
  return atlas_.face_positions(chart, face).transpose() * bary;
}

bool ManifoldSplineSpace::is_home(int chart, int face) const {
  return face >= 0 && face < face_count() && home_row_[face] >= 0 && chart == chart_of(face);
}

std::array<KnotCloud, 3> ManifoldSplineSpace::face_clouds(int chart, int face) const {
  const ChartSpace& cs = chart_space(chart);
  const int row = atlas_.charts[chart].slot(face);
  if (row < 0 || cs.triangle_of_row[row] < 0) {
    throw InvalidInputError("manifold spline: chart " + std::to_string(chart) +
                            " holds no domain " + face_name(face));
  }
  const Eigen::Vector3i& t = cs.space->triangulation().triangles[cs.triangle_of_row[row]];
  const auto& clouds = cs.space->clouds();
  return {clouds[t[0]], clouds[t[1]], clouds[t[2]]};
}

std::vector<ManifoldBasisSample> ManifoldSplineSpace::evaluate_basis(
    const DomainPoint& point, int chart, const TieBreak& tie, BasisDerivatives derivatives) const {
  if (point.face < 0 || point.face >= face_count() || domain_index_[point.face] < 0) {
    throw InvalidInputError("manifold spline: " + face_name(point.face) +
                            " is not in the spline's domain");
  }
  if (chart < 0) chart = chart_of(point.face);
  return evaluate_basis_at(chart, point.face, chart_point(chart, point.face, point.barycentric),
                           tie, derivatives);
}

std::vector<ManifoldBasisSample> ManifoldSplineSpace::evaluate_basis_at(
    int chart, int face, const Eigen::Vector2d& u, const TieBreak& tie,
    BasisDerivatives derivatives) const {
  std::vector<ManifoldBasisSample> out;
  evaluate_basis_at(chart, face, u, tie, derivatives, out);
  return out;
}

void ManifoldSplineSpace::evaluate_basis_at(int chart, int face, const Eigen::Vector2d& u,
                                            const TieBreak& tie, BasisDerivatives derivatives,
                                            std::vector<ManifoldBasisSample>& out) const {
  const ChartSpace& cs = chart_space(chart);
  const int row = is_home(chart, face) ? home_row_[face] : atlas_.charts[chart].slot(face);
  if (row < 0 || cs.triangle_of_row[row] < 0) {
    throw InvalidInputError("manifold spline: chart " + std::to_string(chart) +
                            " holds no domain " + face_name(face));
  }
  // Only the triangles sharing a vertex with the face's (clouds stay inside their vertex stars;
  // in a self-overlapping chart the other sheets' triangles are left out too).
  const int own = cs.triangle_of_row[row];
  thread_local std::vector<int> around;
  thread_local std::vector<BasisSample> samples;
  around.assign(cs.around.begin() + cs.around_start[own],
                cs.around.begin() + cs.around_start[own + 1]);
  samples.clear();
  cs.space->evaluate_basis_of(u, around, tie, derivatives, samples);
  const int m = functions_per_face();
  out.clear();
  out.reserve(samples.size());
  for (const BasisSample& s : samples) {
    out.push_back({domain_index_[cs.face_of_triangle[s.triangle]] * m + s.beta, s.jet});
  }
}

std::vector<int> ManifoldSplineSpace::reaching_faces(int face) const {
  if (face < 0 || face >= face_count() || domain_index_[face] < 0) {
    throw InvalidInputError("manifold spline: " + face_name(face) + " is not in the spline's domain");
  }
  const ChartSpace& cs = chart_space(chart_of(face));
  const int row = atlas_.charts[chart_of(face)].slot(face);
  const Eigen::Vector3i& own = cs.space->triangulation().triangles[cs.triangle_of_row[row]];
  std::vector<int> faces;
  for (int k = 0; k < 3; ++k) {
    for (int t : cs.triangles_at_vertex[own[k]]) faces.push_back(cs.face_of_triangle[t]);
  }
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  return faces;
}

Eigen::MatrixXd ManifoldSplineSpace::control_points_of(const BivariatePolynomial& p,
                                                       int chart) const {
  const ChartSpace& cs = chart_space(chart);
  const int m = functions_per_face();
  Eigen::MatrixXd points = Eigen::MatrixXd::Zero(function_count(), p.coefficients.cols());
  if (!cs.space) return points;
  const auto& clouds = cs.space->clouds();
  for (std::size_t t = 0; t < cs.face_of_triangle.size(); ++t) {
    const Eigen::Vector3i& tri = cs.space->triangulation().triangles[t];
    points.middleRows(domain_index_[cs.face_of_triangle[t]] * m, m) =
        triangle_control_points(p, clouds[tri[0]], clouds[tri[1]], clouds[tri[2]]);
  }
  return points;
}

bool is_partition_of_unity(const std::vector<ManifoldBasisSample>& samples, double tolerance) {
  double sum = 0.0;
  for (const auto& s : samples) sum += s.jet.value;
  return std::abs(sum - 1.0) <= tolerance;
}

SurfaceJet combine(const std::vector<ManifoldBasisSample>& samples,
                   const Eigen::MatrixX3d& control_points, int chart,
                   BasisDerivatives derivatives) {
  SurfaceJet s;
  s.chart = chart;
  // The sums of each order are the same at every order (each field its own sum, in the
  // samples' order), so what a lower order computes has the full evaluation's bits.
  for (const ManifoldBasisSample& b : samples) {
    const Eigen::Vector3d c = control_points.row(b.function).transpose();
    s.position += b.jet.value * c;
    if (derivatives == BasisDerivatives::none) continue;
    s.du += b.jet.gradient.x() * c;
    s.dv += b.jet.gradient.y() * c;
    if (derivatives == BasisDerivatives::first) continue;
    s.duu += b.jet.hessian[0] * c;
    s.duv += b.jet.hessian[1] * c;
    s.dvv += b.jet.hessian[2] * c;
  }
  if (derivatives == BasisDerivatives::none) return s;
  const Eigen::Vector3d n = s.du.cross(s.dv);
  if (n.norm() > 0.0) s.normal = n.normalized();
  return s;
}

SurfaceJet ManifoldSpline::evaluate(const DomainPoint& point, int chart, const TieBreak& tie,
                                    BasisDerivatives derivatives) const {
  if (control_points.rows() != space->function_count()) {
    throw InvalidInputError("manifold spline: " + std::to_string(control_points.rows()) +
                            " control points for " + std::to_string(space->function_count()) +
                            " functions");
  }
  if (point.face < 0 || point.face >= space->face_count() || !space->in_domain(point.face)) {
    throw InvalidInputError("manifold spline: " + face_name(point.face) +
                            " is not in the spline's domain");
  }
  if (chart < 0) chart = space->chart_of(point.face);
  return evaluate_at(chart, point.face,
                     space->chart_point(chart, point.face, point.barycentric), tie, derivatives);
}

SurfaceJet ManifoldSpline::evaluate_at(int chart, int face, const Eigen::Vector2d& u,
                                       const TieBreak& tie, BasisDerivatives derivatives) const {
  // Per-thread samples: surfaces are evaluated point by point in hot loops.
  thread_local std::vector<ManifoldBasisSample> samples;
  space->evaluate_basis_at(chart, face, u, tie, derivatives, samples);
  return combine(samples, control_points, chart, derivatives);
}

}  // namespace spline

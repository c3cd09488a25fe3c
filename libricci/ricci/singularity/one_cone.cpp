#include "ricci/singularity/one_cone.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <queue>
#include <string>
#include <utility>

#include "ricci/intrinsic/flip_free.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/neighbourhoods.h"
#include "ricci/mesh/primitives.h"
#include "ricci/metric/subdivide.h"
#include "ricci/singularity/open_target.h"

namespace ricci {
namespace {

// Rings around a single cone whose edges start with tangent circles (cone_tangent_metric).
constexpr int kConeTangentRings = 3;
// Stages of the continuation tried when the flow to the cone stalls in one go.
constexpr int kConeContinuationStages = 4;

void check_vertex(const Mesh& mesh, int vertex) {
  if (vertex < 0 || vertex >= static_cast<int>(mesh.n_vertices())) {
    throw InvalidInputError("singular vertex " + std::to_string(vertex) + " is out of range (mesh has " +
                            std::to_string(mesh.n_vertices()) + " vertices)");
  }
}

// The mesh without `vertex` and its incident faces; fills input_vertex with the index map.
Mesh remove_star(const Mesh& mesh, int vertex, std::vector<int>& input_vertex) {
  Mesh out;
  std::vector<VertexHandle> new_handle(mesh.n_vertices());
  for (auto v : mesh.vertices()) {
    if (v.idx() == vertex) continue;
    new_handle[v.idx()] = out.add_vertex(mesh.point(v));
    input_vertex.push_back(v.idx());
  }
  for (auto f : mesh.faces()) {
    std::vector<VertexHandle> corners;
    bool touches = false;
    for (auto v : mesh.fv_range(f)) {
      touches = touches || v.idx() == vertex;
      corners.push_back(new_handle[v.idx()]);
    }
    if (!touches) out.add_face(corners);
  }
  return out;
}

const char* radius_name(RadiusInit radii) {
  switch (radii) {
    case RadiusInit::mean:
      return "mean";
    case RadiusInit::min:
      return "min";
    case RadiusInit::least_squares:
      return "least-squares";
  }
  return "unknown";
}

// A metric's name in results and messages: "scheme/radii" (FlowResult::metric_name).
std::string metric_label(Scheme scheme, RadiusInit radii) {
  return to_string(scheme) + "/" + radius_name(radii);
}

std::vector<int> identity_map(int n, int added) {
  std::vector<int> map(static_cast<size_t>(n + added), -1);
  for (int i = 0; i < n; ++i) map[static_cast<size_t>(i)] = i;
  return map;
}

}  // namespace

std::string to_string(OneConeKind kind) {
  switch (kind) {
    case OneConeKind::FlatTorus: return "flat-torus";
    case OneConeKind::SingleCone: return "single-cone";
    case OneConeKind::PuncturedSphere: return "punctured-sphere";
    case OneConeKind::OpenSurface: return "open-surface";
  }
  return "unknown";
}

FlowOptions one_cone_flow_options() {
  FlowOptions options;
  options.scheme = Scheme::circle_packing;
  options.radii = RadiusInit::mean;
  return options;
}

std::vector<std::pair<Scheme, RadiusInit>> one_cone_metric_order(OneConeKind kind) {
  if (kind == OneConeKind::SingleCone) {
    return {{Scheme::circle_packing, RadiusInit::mean},
            {Scheme::circle_packing, RadiusInit::min},
            {Scheme::combinatorial, RadiusInit::mean}};
  }
  return {{Scheme::inversive_distance, RadiusInit::mean},
          {Scheme::inversive_distance, RadiusInit::min},
          {Scheme::circle_packing, RadiusInit::mean},
          {Scheme::combinatorial, RadiusInit::mean}};
}

namespace {

// Vertex distance, in edges, from `cone` (capped at `rings`).
std::vector<int> ring_depth(const MeshTables& t, int cone, int rings) {
  std::vector<std::vector<int>> adjacent(static_cast<size_t>(t.num_vertices()));
  for (int e = 0; e < t.num_edges(); ++e) {
    adjacent[t.edge_vertices(e, 0)].push_back(t.edge_vertices(e, 1));
    adjacent[t.edge_vertices(e, 1)].push_back(t.edge_vertices(e, 0));
  }
  std::vector<int> depth(static_cast<size_t>(t.num_vertices()), rings);
  std::queue<int> queue;
  depth[cone] = 0;
  queue.push(cone);
  while (!queue.empty()) {
    const int v = queue.front();
    queue.pop();
    if (depth[v] + 1 >= rings) continue;
    for (int w : adjacent[v]) {
      if (depth[w] > depth[v] + 1) {
        depth[w] = depth[v] + 1;
        queue.push(w);
      }
    }
  }
  return depth;
}

}  // namespace

namespace {

// Shrinks both radii of every edge with γ_a² + γ_b² > l² (inversive distance below 0) until
// none is left, then recomputes the inversive distances (the lengths are kept).
void make_inversive_distances_nonnegative(const MeshTables& tables, const EdgeLengths& lengths,
                                          CirclePackingMetric& metric) {
  constexpr int kMaxPasses = 200;
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    bool changed = false;
    for (int e = 0; e < tables.num_edges(); ++e) {
      double& a = metric.gamma[tables.edge_vertices(e, 0)];
      double& b = metric.gamma[tables.edge_vertices(e, 1)];
      const double reach = std::hypot(a, b);
      if (reach <= lengths[e]) continue;
      const double scale = lengths[e] / reach * (1.0 - 1e-12);
      a *= scale;
      b *= scale;
      changed = true;
    }
    if (!changed) break;
  }
  for (int e = 0; e < tables.num_edges(); ++e) {
    metric.eta[e] = circle_edge_eta(Geometry::euclidean, metric.gamma[tables.edge_vertices(e, 0)],
                                    metric.gamma[tables.edge_vertices(e, 1)], lengths[e]);
  }
}

}  // namespace

CirclePackingMetric cone_ring_metric(const MeshTables& tables, const EdgeLengths& lengths, int cone,
                                     const ConeRingMetric& rule) {
  CirclePackingMetric metric =
      initial_metric(tables, lengths, Geometry::euclidean, rule.far, rule.radii);
  if (rule.far == Scheme::inversive_distance && rule.nonnegative_inversive_distance) {
    make_inversive_distances_nonnegative(tables, lengths, metric);
  }
  const std::vector<int> depth = ring_depth(tables, cone, rule.rings);
  std::vector<char> near(static_cast<size_t>(tables.num_edges()), 0);
  for (int e = 0; e < tables.num_edges(); ++e) {
    near[e] = std::min(depth[tables.edge_vertices(e, 0)], depth[tables.edge_vertices(e, 1)]) < rule.rings;
  }
  for (int f = 0; f < tables.num_faces() && rule.needle_angle > 0; ++f) {
    const double l[3] = {lengths[tables.face_edges(f, 0)], lengths[tables.face_edges(f, 1)],
                         lengths[tables.face_edges(f, 2)]};
    double theta[3];
    if (triangle_angles(Geometry::euclidean, l, theta) &&
        std::min({theta[0], theta[1], theta[2]}) >= rule.needle_angle) {
      continue;
    }
    for (int k = 0; k < 3; ++k) near[tables.face_edges(f, k)] = 1;
  }
  const Eigen::VectorXd far_eta = metric.eta;
  // Thurston's angle is the inversive distance clamped to [0, pi/2]: the same circles where
  // they overlap by less than a right angle.
  auto near_eta = [&](int e) {
    return rule.near == Scheme::combinatorial ? 1.0 : std::clamp(far_eta[e], 0.0, 1.0);
  };
  for (int e = 0; e < tables.num_edges(); ++e) {
    if (near[e]) metric.eta[e] = near_eta(e);
  }
  // A face with both kinds of edge can fail the triangle inequality; one with `near` edges only
  // cannot (Thurston's circles with angles in [0, pi/2] always make a triangle). So such faces
  // join the near side, until every face is a triangle: the near side only grows.
  bool grew = true;
  while (grew) {
    grew = false;
    for (int f = 0; f < tables.num_faces(); ++f) {
      double l[3], theta[3];
      for (int k = 0; k < 3; ++k) {
        const int e = tables.face_edges(f, k);
        l[k] = circle_edge_length(Geometry::euclidean, metric.gamma[tables.edge_vertices(e, 0)],
                                  metric.gamma[tables.edge_vertices(e, 1)], metric.eta[e]);
      }
      if (triangle_angles(Geometry::euclidean, l, theta)) continue;
      for (int k = 0; k < 3; ++k) {
        const int e = tables.face_edges(f, k);
        if (!near[e]) {
          near[e] = 1;
          metric.eta[e] = near_eta(e);
          grew = true;
        }
      }
    }
  }
  return metric;
}

CirclePackingMetric cone_tangent_metric(const MeshTables& tables, const EdgeLengths& lengths, int cone,
                                        int rings, RadiusInit radii) {
  return cone_ring_metric(tables, lengths, cone,
                          {Scheme::circle_packing, Scheme::combinatorial, rings, radii});
}

namespace {

// Runs the flow with each metric of one_cone_metric_order until one converges; failed runs are
// appended to `failures`.
// `next` replaces `result`, the attempt before it: its linear work counts the attempts' sum.
void take_over(FlowResult& result, FlowResult next) {
  next.linear_work += result.linear_work;
  result = std::move(next);
}

FlowResult try_metrics(const OneConeProblem& problem, const FlowOptions& caller_options,
                       int first_metric, std::vector<std::string>& failures) {
  FlowResult result;
  // Every run below is on problem.mesh: one symbolic analysis serves them all.
  FlowOptions options = caller_options;
  if (!options.factorization_cache) options.factorization_cache = std::make_shared<FactorizationCache>();
  if (problem.kind == OneConeKind::SingleCone) {
    // Thurston's angles from the mesh with tangent circles at the cone: the mesh-conformal
    // circle packing often has no solution at a 10pi cone (genus3_100k), tangency near the cone
    // weakens the existence condition as far as the combinatorial metric's, and the rest of the
    // surface keeps the mesh's angles.
    const std::string name = "circle-packing/mean, tangent within " + std::to_string(kConeTangentRings) +
                             " rings of the cone: ";
    const MeshTables tables = build_mesh_tables(problem.mesh);
    const CirclePackingMetric initial = cone_tangent_metric(
        tables, mesh_edge_lengths(problem.mesh), problem.cone, kConeTangentRings, RadiusInit::mean);
    try {
      // The staged flow below is the fall-back: a first Newton step cut below 1/64 that gains
      // under 2% predicts the one-shot failure (genus2_100k refined to 1.6M faces), so stop there
      // instead of paying three factorisations for it.
      FlowOptions one_shot = options;
      one_shot.give_up_on_short_first_step = true;
      take_over(result, flow(tables, initial, problem.targets, one_shot));
      result.metric_name = name.substr(0, name.size() - 2);
      if (result.converged()) return result;
      failures.push_back(name + to_string(result.status));
      // The same metric with the cone reached in stages: genus2_100k refined to 1.6M faces
      // stalls at error 3 in one go (Newton's first steps are cut to 1/2048 by the line search)
      // and converges in kConeContinuationStages stages.
      take_over(result, flow_by_continuation(tables, initial, problem.targets, options,
                                             ContinuationOptions{kConeContinuationStages}));
      result.metric_name = name.substr(0, name.size() - 2) + ", by continuation";
      if (result.converged()) return result;
      failures.push_back(name + "by continuation: " + to_string(result.status));
    } catch (const InfeasibleTargetError& e) {
      failures.push_back(name + e.what());
    }
  }
  const auto order = one_cone_metric_order(problem.kind);
  const size_t first =
      static_cast<size_t>(std::clamp<int>(first_metric, 0, static_cast<int>(order.size()) - 1));
  for (size_t i = first; i < order.size(); ++i) {
    const auto [scheme, radii] = order[i];
    FlowOptions attempt = options;
    attempt.scheme = scheme;
    attempt.radii = radii;
    take_over(result, flow(problem.mesh, problem.targets, attempt));
    result.metric_name = metric_label(scheme, radii);
    if (result.converged()) break;
    failures.push_back(metric_label(scheme, radii) + ": " + to_string(result.status));
  }
  return result;
}

}  // namespace

namespace {

// The harmonic boundary target where every boundary angle stays positive (a sharp corner can
// ask for more than pi), else the curvature spread by length.
Targets open_surface_target(const Mesh& mesh) {
  Targets harmonic = harmonic_boundary_target(mesh);
  const double margin = 1e-3;
  if ((harmonic.curvature.array() < M_PI - margin).all()) return harmonic;
  return boundary_target(mesh, BoundaryMode::spread_by_length);
}

// Boundary targets to try after the problem's own, for open surfaces.
std::vector<std::pair<std::string, Targets>> alternative_boundary_targets(const OneConeProblem& problem) {
  std::vector<std::pair<std::string, Targets>> out;
  if (problem.kind != OneConeKind::OpenSurface) return out;
  Targets by_length = boundary_target(problem.mesh, BoundaryMode::spread_by_length);
  if (by_length.curvature != problem.targets.curvature) {
    out.emplace_back("boundary curvature spread by length", std::move(by_length));
  }
  if (problem.boundary_loops > 1) {
    out.emplace_back("circle domain", boundary_target(problem.mesh, BoundaryMode::circle_domain));
  }
  return out;
}

}  // namespace

std::string to_string(const ConeRingMetric& rule) {
  return metric_label(rule.far, rule.radii) + ", " +
         (rule.near == Scheme::combinatorial ? std::string("tangent") : to_string(rule.near)) +
         " within " + std::to_string(rule.rings) + " rings of the cone";
}

FlowResult solve_cone_ring_flow(const OneConeProblem& problem, const std::vector<ConeRingMetric>& rules,
                                const FlowOptions& options, const ContinuationOptions& continuation) {
  if (problem.kind != OneConeKind::SingleCone) {
    throw InvalidInputError("a cone-ring metric needs a single-cone problem, not " + to_string(problem.kind));
  }
  FlowResult result;
  std::vector<std::string> failures;
  const MeshTables tables = build_mesh_tables(problem.mesh);
  const EdgeLengths lengths = mesh_edge_lengths(problem.mesh);
  FlowOptions shared = options;  // one symbolic analysis for every rule's stages
  if (!shared.factorization_cache) shared.factorization_cache = std::make_shared<FactorizationCache>();
  for (const ConeRingMetric& rule : rules) {
    try {
      const CirclePackingMetric initial = cone_ring_metric(tables, lengths, problem.cone, rule);
      // Mixing clamped and free weights in one face can break it before the flow starts: the
      // continuation's first curvature evaluation throws InvalidInputError then.
      take_over(result, flow_by_continuation(tables, initial, problem.targets, shared, continuation));
      result.metric_name = to_string(rule);
      if (result.converged()) break;
      failures.push_back(to_string(rule) + ": " + result.message);
    } catch (const InfeasibleTargetError& e) {
      failures.push_back(to_string(rule) + ": " + e.what());
    } catch (const InvalidInputError& e) {
      failures.push_back(to_string(rule) + ": " + e.what());
    }
  }
  result.failed_attempts.insert(result.failed_attempts.begin(), failures.begin(), failures.end());
  return result;
}

int metric_order_position(OneConeKind kind, const std::string& metric_name) {
  const auto order = one_cone_metric_order(kind);
  for (size_t i = 0; i < order.size(); ++i) {
    if (metric_name == metric_label(order[i].first, order[i].second)) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

FlowResult solve_one_cone_flow(const OneConeProblem& problem, const FlowOptions& options,
                               bool keep_metric, int first_metric) {
  if (keep_metric) {
    FlowResult result = flow(problem.mesh, problem.targets, options);
    result.metric_name = metric_label(options.scheme, options.radii);
    return result;
  }
  std::vector<std::string> failures;
  FlowResult result = try_metrics(problem, options, first_metric, failures);
  for (auto& [name, targets] : alternative_boundary_targets(problem)) {
    if (result.converged()) break;
    OneConeProblem other = problem;
    other.targets = std::move(targets);
    failures.push_back("failed with every metric; trying the boundary target: " + name);
    FlowResult next = try_metrics(other, options, first_metric, failures);
    if (next.converged()) {
      take_over(result, std::move(next));
    } else {
      result.linear_work += next.linear_work;
    }
  }
  result.failed_attempts.insert(result.failed_attempts.begin(), failures.begin(), failures.end());
  return result;
}

bool needs_singular_vertex(const Mesh& mesh) { return needs_singular_vertex(surface_topology(mesh)); }

bool needs_singular_vertex(const SurfaceTopology& topology) {
  return topology.boundary_loops == 0 && topology.genus != 1;
}

namespace {

OneConeProblem prepare_on(const Mesh& mesh, int vertex, const ValenceOptions& valence) {
  OneConeProblem problem;
  const SurfaceTopology topology = surface_topology(mesh);
  problem.genus = topology.genus;
  problem.boundary_loops = topology.boundary_loops;
  const int n = static_cast<int>(mesh.n_vertices());
  if (problem.boundary_loops > 0 || problem.genus == 1) {
    problem.kind = problem.boundary_loops > 0 ? OneConeKind::OpenSurface : OneConeKind::FlatTorus;
    problem.mesh = mesh;
    problem.input_vertex = identity_map(n, 0);
    // No cone on these topologies. Open surfaces: the harmonic boundary target keeps the
    // boundary's lengths (least area distortion; the others are fall-backs in the solve).
    problem.targets = problem.kind == OneConeKind::OpenSurface ? open_surface_target(problem.mesh)
                                                                : single_cone_target(problem.mesh, 0);
    return problem;
  }
  check_vertex(mesh, vertex);
  problem.chosen_vertex = vertex;
  if (problem.genus == 0) {
    problem.kind = OneConeKind::PuncturedSphere;
    problem.mesh = remove_star(mesh, vertex, problem.input_vertex);
    problem.targets = boundary_target(problem.mesh, BoundaryMode::spread_by_length);
    return problem;
  }
  problem.kind = OneConeKind::SingleCone;
  ValenceOptions options = valence;
  options.cone_curvature = 2.0 * M_PI * topology.euler_characteristic;
  ValenceResult modified = modify_valence(mesh, mesh.vertex_handle(vertex), options);
  problem.mesh = std::move(modified.mesh);
  problem.cone = vertex;
  problem.valence_splits = modified.splits;
  problem.input_vertex = identity_map(n, modified.splits);
  problem.targets = single_cone_target(problem.mesh, vertex);
  return problem;
}

// prepare_on after the thin handles' subdivision, `wrapped` being the mesh's
// non_disk_face_neighbourhoods.
OneConeProblem prepare_refined(const Mesh& mesh, int vertex, const ValenceOptions& valence,
                               std::vector<char> wrapped) {
  // Thin handles first: a face whose neighbourhood wraps around one cannot get a chart.
  // Only the faces whose neighbourhood wraps are split (red-green), so the mesh grows by the
  // thin parts alone (a simplified horse's legs), not four-fold.
  Mesh refined;
  int subdivisions = 0;
  while (subdivisions < kMaxHandleSubdivisions) {
    if (subdivisions > 0) wrapped = non_disk_face_neighbourhoods(refined);
    if (std::find(wrapped.begin(), wrapped.end(), 1) == wrapped.end()) break;
    refined = subdivide_midpoint_locally(subdivisions > 0 ? refined : mesh, wrapped);
    ++subdivisions;
  }
  if (subdivisions == 0) return prepare_on(mesh, vertex, valence);
  OneConeProblem problem = prepare_on(refined, vertex, valence);
  problem.subdivisions = subdivisions;
  // Midpoint subdivision keeps the input's vertex indices and appends the midpoints.
  const int n = static_cast<int>(mesh.n_vertices());
  for (int& v : problem.input_vertex) {
    if (v >= n) v = -1;
  }
  return problem;
}

}  // namespace

OneConeProblem prepare_one_cone(const Mesh& mesh, int vertex, const ValenceOptions& valence,
                                bool refine_thin_handles) {
  if (!refine_thin_handles) return prepare_on(mesh, vertex, valence);
  return prepare_refined(mesh, vertex, valence, non_disk_face_neighbourhoods(mesh));
}

OneConeProblem prepare_one_cone(const Mesh& mesh, int vertex, const ValenceOptions& valence,
                                const std::vector<char>& non_disk_faces) {
  if (non_disk_faces.size() != mesh.n_faces()) {
    throw InvalidInputError("non-disk face flags: " + std::to_string(non_disk_faces.size()) +
                            " for " + std::to_string(mesh.n_faces()) + " faces");
  }
  return prepare_refined(mesh, vertex, valence, non_disk_faces);
}

namespace {

// Vertices fewer than `rings` edges from `cone`.
std::vector<char> vertices_near(const Mesh& mesh, int cone, int rings) {
  std::vector<char> near_vertex(mesh.n_vertices(), 0);
  std::vector<int> frontier{cone};
  near_vertex[static_cast<size_t>(cone)] = 1;
  for (int ring = 1; ring < rings; ++ring) {
    std::vector<int> next;
    for (int v : frontier) {
      for (auto w : mesh.vv_range(mesh.vertex_handle(v))) {
        if (near_vertex[static_cast<size_t>(w.idx())]) continue;
        near_vertex[static_cast<size_t>(w.idx())] = 1;
        next.push_back(w.idx());
      }
    }
    frontier = std::move(next);
  }
  return near_vertex;
}

// Faces with a corner fewer than `rings` edges from `cone`.
std::vector<char> faces_near(const Mesh& mesh, int cone, int rings) {
  const std::vector<char> near_vertex = vertices_near(mesh, cone, rings);
  std::vector<char> faces(mesh.n_faces(), 0);
  for (auto f : mesh.faces()) {
    for (auto v : mesh.fv_range(f)) {
      faces[static_cast<size_t>(f.idx())] |= near_vertex[static_cast<size_t>(v.idx())];
    }
  }
  return faces;
}

// Edges between `near` vertices, off the cone's faces, whose ends' distances from the cone give
// a chart ratio alpha |ln(rho_b / rho_a)| above `chart_log` (ConeRefinementOptions).
std::vector<int> radially_long_edges(const Mesh& mesh, int cone, const std::vector<char>& near,
                                     double alpha, double chart_log) {
  const Mesh::Point apex = mesh.point(mesh.vertex_handle(static_cast<unsigned>(cone)));
  std::vector<int> edges;
  for (auto e : mesh.edges()) {
    const HalfedgeHandle h = mesh.halfedge_handle(e, 0);
    const VertexHandle a = mesh.from_vertex_handle(h);
    const VertexHandle b = mesh.to_vertex_handle(h);
    if (a.idx() == cone || b.idx() == cone || !near[static_cast<size_t>(a.idx())] ||
        !near[static_cast<size_t>(b.idx())] || mesh.opposite_vh(h).idx() == cone ||
        mesh.opposite_he_opposite_vh(h).idx() == cone) {
      continue;  // the cone keeps its valence
    }
    const double rho_a = (mesh.point(a) - apex).norm();
    const double rho_b = (mesh.point(b) - apex).norm();
    if (rho_a > 0.0 && rho_b > 0.0 && alpha * std::abs(std::log(rho_b / rho_a)) > chart_log) {
      edges.push_back(e.idx());
    }
  }
  return edges;
}

// The radial grading of ConeRefinementOptions over the vertices within radial_rings rings of the
// cone before it (the midpoints join them); returns the number of edges split.
int grade_radially(OneConeProblem& problem, const ConeRefinementOptions& options) {
  const double alpha = 2.0 * problem.genus - 1.0;
  std::vector<char> near = vertices_near(problem.mesh, problem.cone, options.radial_rings);
  if (options.radial_inner_rings > 0) {
    const std::vector<char> inner =
        vertices_near(problem.mesh, problem.cone, options.radial_inner_rings);
    for (size_t v = 0; v < near.size(); ++v) near[v] = static_cast<char>(near[v] && !inner[v]);
  }
  int splits = 0;
  for (int level = 0; level < options.radial_levels; ++level) {
    const std::vector<int> edges =
        radially_long_edges(problem.mesh, problem.cone, near, alpha, options.radial_chart_log);
    if (edges.empty()) break;
    splits += split_edges_at_midpoints(problem.mesh, edges);
    near.resize(problem.mesh.n_vertices(), 1);
  }
  return splits;
}

}  // namespace

ConeRefinement refine_around_cone(OneConeProblem& problem, const ConeRefinementOptions& options) {
  if (options.radial_levels < 0 || options.radial_rings < 1 || !(options.radial_chart_log > 0.0)) {
    throw InvalidInputError(
        "radial cone refinement needs radial_levels >= 0, radial_rings >= 1 and "
        "radial_chart_log > 0");
  }
  if (options.levels < 0 || options.rings < 1) {
    throw InvalidInputError("cone refinement needs levels >= 0 and rings >= 1, got " +
                            std::to_string(options.levels) + " and " + std::to_string(options.rings));
  }
  ConeRefinement done;
  if (problem.kind != OneConeKind::SingleCone || options.levels == 0) return done;
  const auto faces_before = static_cast<int>(problem.mesh.n_faces());
  for (; done.levels < options.levels; ++done.levels) {
    problem.mesh =
        subdivide_midpoint_locally(problem.mesh, faces_near(problem.mesh, problem.cone, options.rings));
  }
  if (options.radial_from_genus > 0 && problem.genus >= options.radial_from_genus) {
    done.radial_splits = grade_radially(problem, options);
  }
  done.added_faces = static_cast<int>(problem.mesh.n_faces()) - faces_before;
  // Midpoint subdivision keeps vertex indices and appends the midpoints.
  problem.input_vertex.resize(problem.mesh.n_vertices(), -1);
  problem.targets = single_cone_target(problem.mesh, problem.cone);
  return done;
}

}  // namespace ricci

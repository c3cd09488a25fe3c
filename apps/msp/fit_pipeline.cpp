#include "msp/fit_pipeline.h"

#include "msp/fit_fill.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <ctime>
#include <string>
#include <unordered_map>

#include <ricci/mesh/errors.h>
#include <ricci/mesh/simplify.h>
#include <spline/tessellate/parallel_for.h>

namespace msp {
namespace {

using Clock = std::chrono::steady_clock;

double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

Eigen::MatrixX3d vertex_matrix(const ricci::Mesh& mesh) {
  Eigen::MatrixX3d points(static_cast<Eigen::Index>(mesh.n_vertices()), 3);
  for (auto v : mesh.vertices()) points.row(v.idx()) = ricci::to_eigen(mesh.point(v)).transpose();
  return points;
}

// Closed surfaces other than tori carry an extraordinary point; open ones and tori none.
bool needs_singularity(const ricci::SurfaceTopology& t) {
  return t.boundary_loops == 0 && t.genus != 1;
}

// The interior vertex of `domain` nearest to `point`.
int nearest_interior_vertex(const ricci::Mesh& domain, const Eigen::Vector3d& point) {
  int best = -1;
  double best_distance = 0.0;
  for (auto v : domain.vertices()) {
    if (domain.is_boundary(v)) continue;
    const double d = (ricci::to_eigen(domain.point(v)) - point).squaredNorm();
    if (best < 0 || d < best_distance) {
      best = v.idx();
      best_distance = d;
    }
  }
  return best;
}

// The user's singular vertex (an index of the input) as a vertex of the domain mesh fit_scan
// will build: the simplification is deterministic, so running it here gives the same mesh.
int domain_singular_vertex(const ricci::Mesh& dense, const FitRunOptions& options) {
  const int v = options.singular_vertex;
  if (v < 0) return -1;
  if (v >= static_cast<int>(dense.n_vertices())) {
    throw ricci::InvalidInputError("singular vertex " + std::to_string(v) +
                                   " is out of range (the mesh has " +
                                   std::to_string(dense.n_vertices()) + " vertices)");
  }
  if (dense.is_boundary(dense.vertex_handle(v))) {
    throw ricci::InvalidInputError("singular vertex " + std::to_string(v) +
                                   " lies on the boundary (the extraordinary point must be an "
                                   "interior vertex)");
  }
  if (static_cast<int>(dense.n_faces()) <= options.domain_faces) return v;
  ricci::SimplifyOptions simplify;
  simplify.target_faces = options.domain_faces;
  const ricci::Mesh domain = ricci::simplify_mesh(dense, simplify).mesh;
  return nearest_interior_vertex(domain, ricci::to_eigen(dense.point(dense.vertex_handle(v))));
}

// Gauss-Newton steps of the projection: the distance is stationary in the parameter, so its
// error is second order in the step left. Measured on cup.off (5.7k vertices): 6 -> 2 steps
// moves the RMS by 0.07% of itself and the maximum not at all, for half the evaluations
// (the measure stage of a 100k-face scan is dominated by these projections).
constexpr int kProjectionIterations = 2;

// Distances of the input's vertices to the surface shown: the spline by closest-point
// projection from their parameters; vertices whose parameter is outside the tessellated faces
// (the cone's star, a fill's covered faces) to the nearest fill patch. In parallel.
void measure_fit(const ricci::Mesh& dense, const spline::ScanFitResult& scan,
                 const std::vector<char>& skip, FitRun& run) {
  const Eigen::MatrixX3d points = vertex_matrix(dense);
  std::vector<double> distance(static_cast<std::size_t>(points.rows()), -1.0);
  std::vector<char> on_fill(distance.size(), 0);
  spline::parallel_for(distance.size(), 0, [&](std::size_t k) {
    const spline::DomainPoint& start = scan.vertex_parameters[k];
    const Eigen::Vector3d target = points.row(static_cast<Eigen::Index>(k)).transpose();
    if (start.face >= 0 && !skip[static_cast<std::size_t>(start.face)]) {
      distance[k] =
          spline::project_to_spline(scan.spline, start, target, kProjectionIterations).distance;
      return;
    }
    distance[k] = distance_to_fills(run, target, kProjectionIterations);
    on_fill[k] = distance[k] >= 0;
  });
  for (char c : on_fill) run.fit_points_on_fills += c;
  double sum = 0.0;
  for (double d : distance) {
    if (d < 0) continue;
    sum += d * d;
    run.fit_max = std::max(run.fit_max, d);
    ++run.fit_points;
  }
  run.fit_rms = run.fit_points > 0 ? std::sqrt(sum / run.fit_points) : 0.0;
  run.bbox_diagonal =
      points.rows() > 0 ? (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm() : 0.0;
}

// The tessellation as a glTF reader sees it: float positions, equal ones welded.
spline::WatertightReport float_welded_topology(const spline::Tessellation& t) {
  struct Key {
    float x, y, z;
    bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  struct Hash {
    std::size_t operator()(const Key& k) const {
      std::uint32_t b[3];
      std::memcpy(b, &k, sizeof b);
      return (std::size_t{b[0]} * 0x9E3779B1u) ^ (std::size_t{b[1]} * 0x85EBCA77u) ^ b[2];
    }
  };
  std::unordered_map<Key, int, Hash> index;
  std::vector<int> welded(static_cast<std::size_t>(t.positions.rows()));
  std::vector<Key> keys;
  for (Eigen::Index i = 0; i < t.positions.rows(); ++i) {
    const Key k{static_cast<float>(t.positions(i, 0)), static_cast<float>(t.positions(i, 1)),
                static_cast<float>(t.positions(i, 2))};
    auto [it, inserted] = index.emplace(k, static_cast<int>(keys.size()));
    if (inserted) keys.push_back(k);
    welded[static_cast<std::size_t>(i)] = it->second;
  }
  Eigen::MatrixX3d positions(static_cast<Eigen::Index>(keys.size()), 3);
  for (std::size_t i = 0; i < keys.size(); ++i)
    positions.row(static_cast<Eigen::Index>(i)) << keys[i].x, keys[i].y, keys[i].z;
  std::vector<std::array<int, 3>> triangles;
  triangles.reserve(t.triangles.size());
  for (const auto& tri : t.triangles)
    triangles.push_back({welded[static_cast<std::size_t>(tri[0])],
                         welded[static_cast<std::size_t>(tri[1])],
                         welded[static_cast<std::size_t>(tri[2])]});
  return spline::check_watertight(triangles, positions);
}

// Density: about 120k surface triangles in all (smooth shading at any zoom a viewer starts
// with, a few MB of glb), 2..8 samples per domain edge.
int chosen_density(const FitRunOptions& options, int domain_faces) {
  if (options.density > 0) return options.density;
  const double d = std::sqrt(120000.0 / std::max(1, domain_faces));
  return std::clamp(static_cast<int>(std::lround(d)), 2, 8);
}

}  // namespace

int minimum_domain_faces(int genus) { return 100 * std::max(1, genus + 1); }

FitRun run_fit_pipeline(const ricci::Mesh& dense, const FitRunOptions& options) {
  FitRun run;
  const auto total = Clock::now();
  run.input = ricci::surface_topology(dense);
  const int minimum = minimum_domain_faces(run.input.genus);
  if (options.domain_faces < minimum) {
    throw ricci::InvalidInputError("--domain-faces " + std::to_string(options.domain_faces) +
                                   " is too few for a genus-" + std::to_string(run.input.genus) +
                                   " surface (at least " + std::to_string(minimum) + ")");
  }
  if (static_cast<int>(dense.n_faces()) < minimum) {
    throw ricci::InvalidInputError("the mesh has " + std::to_string(dense.n_faces()) +
                                   " faces, too few for a genus-" +
                                   std::to_string(run.input.genus) + " spline domain (at least " +
                                   std::to_string(minimum) + ")");
  }

  auto stage_start = Clock::now();
  double cpu_start = process_cpu_seconds();
  const double cpu_total = cpu_start;
  std::string stage;
  auto begin = [&](const std::string& name) {
    if (!stage.empty()) {
      run.seconds.emplace_back(stage, seconds_since(stage_start));
      run.cpu_seconds.emplace_back(stage, process_cpu_seconds() - cpu_start);
    }
    cpu_start = process_cpu_seconds();
    stage = name;
    stage_start = Clock::now();
    if (options.progress) options.progress(name);
  };

  spline::ScanFitOptions scan;
  scan.domain_faces = options.domain_faces;
  scan.degree = options.degree;
  scan.fair_r = options.fairness;
  scan.fit.smoothing = options.smoothing;
  scan.atlas.cone_refinement = options.cone_refinement;
  if (options.singular_vertex >= 0) {
    begin("singularity");
    if (needs_singularity(run.input)) {
      scan.atlas.singular_vertex = domain_singular_vertex(dense, options);
    } else {
      (void)domain_singular_vertex(dense, options);  // checks range and boundary only
    }
  }
  scan.progress = begin;
  run.scan = spline::fit_scan(dense, scan);
  const auto& problem = run.scan.atlas.problem;
  run.singular_domain_vertex = problem.cone >= 0 ? run.scan.atlas.chosen_vertex : -1;

  const ricci::Mesh& domain = problem.mesh;
  begin("fill");
  const std::vector<char> skip = fill_rims(run, domain, options);

  begin("tessellate");
  spline::TessellationOptions tess;
  tess.density = chosen_density(options, run.scan.spline.space->domain_face_count());
  tess.skip_faces = skip;
  run.tessellation = spline::tessellate(run.scan.spline, domain, tess);
  append_fills(run);

  begin("measure");
  run.topology = spline::check_watertight(run.tessellation.triangles, run.tessellation.positions);
  // The rims left open on purpose: each is one boundary loop of the result (nearby input loops
  // merged into one rim count once).
  const int expected_loops = run.open_rims - static_cast<int>(run.fill_failures.size());
  run.float_topology = float_welded_topology(run.tessellation);
  run.surface_dihedral =
      spline::dihedral_angles(run.tessellation.triangles, run.tessellation.positions);
  run.watertight = run.topology.matches(run.input.genus, expected_loops) &&
                   run.float_topology.matches(run.input.genus, expected_loops);
  run.edge_normal_jump_deg = spline::max_edge_normal_jump_deg(run.scan.spline, domain, 1, 0, skip);
  measure_fit(dense, run.scan, skip, run);
  begin("");
  run.seconds.emplace_back("total", seconds_since(total));
  run.cpu_seconds.emplace_back("total", process_cpu_seconds() - cpu_total);
  return run;
}

nlohmann::json fit_report_json(const std::string& path, const FitRun& run,
                               const FitRunOptions& options) {
  const auto& atlas = run.scan.atlas;
  const auto& space = *run.scan.spline.space;
  nlohmann::json singularities = nlohmann::json::array();
  if (atlas.problem.cone >= 0) {
    const double K = atlas.flow.curvature[atlas.problem.cone];
    const auto p = atlas.problem.mesh.point(atlas.problem.mesh.vertex_handle(atlas.problem.cone));
    singularities.push_back({{"domain_vertex", run.singular_domain_vertex},
                             {"input_vertex", options.singular_vertex},
                             {"position", {p[0], p[1], p[2]}},
                             {"curvature", K},
                             {"cone_angle", 2 * M_PI - K}});
  } else if (atlas.problem.kind == ricci::OneConeKind::PuncturedSphere) {
    singularities.push_back({{"domain_vertex", atlas.chosen_vertex},
                             {"input_vertex", options.singular_vertex},
                             {"removed_star", true}});
  }
  nlohmann::json seconds = nlohmann::json::object();
  for (const auto& [name, s] : run.seconds) seconds[name] = s;
  nlohmann::json cpu_seconds = nlohmann::json::object();
  for (const auto& [name, s] : run.cpu_seconds) cpu_seconds[name] = s;
  const double diag = std::max(run.bbox_diagonal, 1e-300);
  const auto& t = run.topology;
  return {
      {"mesh", path},
      {"input_vertices", run.input.vertices},
      {"input_faces", run.input.faces},
      {"genus", run.input.genus},
      {"boundary_loops", run.input.boundary_loops},
      {"singularities", singularities},
      {"domain_faces", space.domain_face_count()},
      {"domain_mesh_faces", atlas.problem.mesh.n_faces()},
      {"cone_refinement",
       {{"levels", atlas.cone_refinement.levels},
        {"rings", options.cone_refinement.rings},
        {"added_faces", atlas.cone_refinement.added_faces}}},
      {"control_points", space.function_count()},
      {"degree", space.degree()},
      {"fairness", options.fairness},
      {"fit_rms", run.fit_rms},
      {"fit_max", run.fit_max},
      {"fit_rms_relative", run.fit_rms / diag},
      {"fit_max_relative", run.fit_max / diag},
      {"fit_points", run.fit_points},
      {"bbox_diagonal", run.bbox_diagonal},
      {"seam_normal_jump_max_deg", std::max(run.edge_normal_jump_deg, run.fill_normal_jump_deg)},
      {"edge_normal_jump_max_deg", run.edge_normal_jump_deg},
      {"fill_normal_jump_max_deg", run.fill_normal_jump_deg},
      {"fill_position_gap_relative", run.fill_position_gap},
      {"filled_rims", run.filled_rims},
      {"fill_failures", run.fill_failures},
      {"fit_points_on_fills", run.fit_points_on_fills},
      {"open_rims", run.open_rims},
      {"boundary_rims", run.boundary_rims},
      {"fallback_fills", run.fallback_fills},
      {"watertight", run.watertight},
      {"tessellation",
       {{"density", run.tessellation.density},
        {"vertices", t.vertices},
        {"triangles", t.faces},
        {"render_vertices", run.tessellation.uvs.rows()},
        {"euler_characteristic", t.euler_characteristic},
        {"boundary_loops", t.boundary_loops},
        {"boundary_edges", t.boundary_edges},
        {"nonmanifold_edges", t.nonmanifold_edges},
        {"misoriented_edges", t.misoriented_edges},
        {"nonmanifold_vertices", t.nonmanifold_vertices},
        {"duplicate_positions", t.duplicate_positions},
        {"float32_degenerate_triangles", run.float_topology.degenerate_triangles},
        {"float32_nonmanifold_edges", run.float_topology.nonmanifold_edges}}},
      {"surface_dihedral",
       {{"edges", run.surface_dihedral.edges},
        {"median_deg", run.surface_dihedral.median_deg},
        {"p99_deg", run.surface_dihedral.p99_deg},
        {"max_deg", run.surface_dihedral.max_deg},
        {"edges_over_60_deg", run.surface_dihedral.over_60_deg},
        {"edges_over_90_deg", run.surface_dihedral.over_90_deg}}},
      {"fit_constraint_residual", run.scan.fit.max_constraint_residual},
      {"seconds", seconds},
      {"cpu_seconds", cpu_seconds},
  };
}

}  // namespace msp

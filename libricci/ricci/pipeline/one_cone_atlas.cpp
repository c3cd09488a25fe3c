#include "ricci/pipeline/one_cone_atlas.h"

#include "ricci/metric/polish_e2.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <sstream>
#include <utility>

#include "ricci/mesh/arrays.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/neighbourhoods.h"
#include "ricci/mesh/primitives.h"
#include "ricci/metric/mesh_tables.h"
#include "ricci/util/edge_key.h"
#include "ricci/util/memory.h"
#include "ricci/util/parallel.h"
#include "ricci/util/stopwatch.h"

namespace ricci {
namespace {

// The cut graph's root on the problem's mesh (or one of the same connectivity): the cone, else
// an interior vertex (genus 1) or vertex 0 (open).
VertexHandle atlas_root(const OneConeProblem& problem, const Mesh& mesh) {
  if (problem.cone >= 0) return mesh.vertex_handle(problem.cone);
  for (auto v : mesh.vertices()) {
    if (!mesh.is_boundary(v)) return v;
  }
  return mesh.vertex_handle(0);
}

// The input surface as the pipeline holds it: the caller's mesh, kept all along, or one handed
// over (build_one_cone_atlas(Mesh&&)), which waits as (V, F) arrays once a problem's mesh is
// made from it (fold: 38 MB against OpenMesh's 126 at 1.6M faces, beside the flow's
// factorisation), is rebuilt in place in the same vertex and face order only if a later route
// needs it (a fallback after a failed flow), and is left empty. (OpenMesh meshes have no move
// constructor: std::move would copy them, so the handed-over mesh is used where it is.)
class InputSurface {
 public:
  static InputSurface kept(const Mesh& mesh) { return InputSurface(&mesh, nullptr); }
  static InputSurface handed_over(Mesh& mesh) { return InputSurface(&mesh, &mesh); }
  InputSurface(const InputSurface&) = delete;
  InputSurface& operator=(const InputSurface&) = delete;
  ~InputSurface() {
    if (handed_ != nullptr) handed_->clear();
  }

  const Mesh& mesh() {
    if (mesh_ == nullptr) {
      *handed_ = same_order_mesh(arrays_);
      arrays_ = VertexFaceArrays();
      mesh_ = handed_;
    }
    return *mesh_;
  }

  // The input's faces whose neighbourhood is not a disk (non_disk_face_neighbourhoods), once
  // computed: it needs no cone, so it is made beside the choice's factorisation. Rebuilding the
  // mesh keeps its face order, and with it the flags.
  void set_non_disk_faces(std::vector<char> flags) { non_disk_faces_ = std::move(flags); }
  [[nodiscard]] const std::vector<char>& non_disk_faces() const { return non_disk_faces_; }

  // A handed-over mesh becomes arrays (clear(): assigning an empty Mesh keeps OpenMesh's
  // arrays' capacity); the caller's kept mesh stays as it is.
  void fold() {
    if (handed_ == nullptr || mesh_ == nullptr) return;
    arrays_ = to_arrays(*handed_);
    handed_->clear();
    mesh_ = nullptr;
  }

 private:
  InputSurface(const Mesh* mesh, Mesh* handed) : mesh_(mesh), handed_(handed) {}

  const Mesh* mesh_;  // null while folded
  Mesh* handed_;      // null when kept
  VertexFaceArrays arrays_;
  std::vector<char> non_disk_faces_;
};

// Index in the cleaned-up mesh of input vertex `vertex` (-1 stays -1).
int input_to_cleaned(const OneConeAtlasResult& result, int vertex) {
  const std::vector<int>& map = result.short_edges.input_vertex;
  if (vertex < 0 || map.empty()) return vertex;
  return static_cast<int>(std::find(map.begin(), map.end(), vertex) - map.begin());
}

// The input with its short edges collapsed and its flat non-Delaunay edges flipped, as asked;
// fills result.short_edges (with the vertex map) and result.flat_flips.
Mesh clean_up_surface(const Mesh& mesh, const OneConeAtlasOptions& options, OneConeAtlasResult& result) {
  Mesh cleaned = mesh;
  if (options.collapse_short_edges) {
    ShortEdgeOptions short_edges = options.short_edges;
    short_edges.keep_vertex = result.chosen_vertex;
    result.short_edges = collapse_short_edges(mesh, short_edges);
    cleaned = result.short_edges.mesh;
    result.short_edges.mesh.clear();  // the problem's mesh is the one kept
  }
  if (options.flip_flat_edges) {
    FlatFlipOptions flips = options.flat_flips;
    flips.protected_vertex = input_to_cleaned(result, result.chosen_vertex);
    result.flat_flips = flip_flat_edges_to_delaunay(cleaned, flips);
  }
  return cleaned;
}

// prepare_one_cone indexed the problem by the cleaned-up mesh: back to the input's indices.
void map_problem_to_input(OneConeAtlasResult& result) {
  const std::vector<int>& map = result.short_edges.input_vertex;
  if (map.empty()) return;
  for (int& v : result.problem.input_vertex) {
    if (v >= 0) v = map[static_cast<size_t>(v)];
  }
  result.problem.chosen_vertex = result.chosen_vertex;
}

// Clean-up, valence modification and cone refinement: fills result's problem and timings;
// then the input, which the flow does not read, is folded.
void prepare_problem(InputSurface& input, const OneConeAtlasOptions& options,
                     OneConeAtlasResult& result, const std::function<void(const char*)>& report) {
  StageTimer t;
  const Mesh& mesh = input.mesh();
  Mesh cleaned;
  const Mesh* surface = &mesh;  // no copy of the input unless it is cleaned up
  if (options.collapse_short_edges || options.flip_flat_edges) {
    report("surface clean-up");
    cleaned = clean_up_surface(mesh, options, result);
    surface = &cleaned;
  }
  result.timings.flips = t.wall.seconds();

  report("valence modification");
  t.restart();
  const int cone = input_to_cleaned(result, result.chosen_vertex);
  const bool flagged = surface == &mesh && input.non_disk_faces().size() == mesh.n_faces();
  result.problem = flagged ? prepare_one_cone(mesh, cone, options.valence, input.non_disk_faces())
                           : prepare_one_cone(*surface, cone, options.valence);
  map_problem_to_input(result);
  result.cone_refinement = refine_around_cone(result.problem, options.cone_refinement);
  input.fold();
  result.timings.valence = t.wall.seconds();
  result.timings.cpu_valence = t.cpu.seconds();
}

// prepare_problem, then the flow: the cone-ring metrics first (single cones), then, when
// `fall_back`, solve_one_cone_flow. Fills result's problem, flow and their timings.
void prepare_and_solve(InputSurface& input, const OneConeAtlasOptions& options,
                       OneConeAtlasResult& result, const std::function<void(const char*)>& report,
                       bool fall_back) {
  prepare_problem(input, options, result, report);
  report("Ricci flow");
  StageTimer t;
  result.flow = FlowResult();
  if (result.problem.kind == OneConeKind::SingleCone && !options.cone_ring_metrics.empty()) {
    result.flow = solve_cone_ring_flow(result.problem, options.cone_ring_metrics, options.flow, options.continuation);
  }
  if (!result.flow.converged() && fall_back) {
    std::vector<std::string> failures = result.flow.failed_attempts;
    result.flow = solve_one_cone_flow(result.problem, options.flow, options.keep_metric);
    result.flow.failed_attempts.insert(result.flow.failed_attempts.begin(), failures.begin(), failures.end());
  }
  result.timings.flow = t.wall.seconds();
  result.timings.cpu_flow = t.cpu.seconds();
}

// Where the intrinsic flow hands over to the long-double polish (solve_intrinsic).
constexpr double kPolishHandover = 1e-9;

// The defect at which that polish stops (polish_e2_lengths' good_enough): from the handover
// one step lands near the long-double evaluation's floor (4-9e-15 at 100k faces), and a step
// from there only measures the floor. Well below the femur's 1.4e-13, which gave 1e-9
// relative error on its shortest edge.
constexpr double kPolishGoal = 1e-14;

// A flow that stalled this close to the target only met the rounding floor of double
// precision (genus3_10k's inversive-distance route stops at 2.5e-10 > 1e-10).
constexpr double kPolishableError = 1e-8;

// The long-double polish of the flow's lengths (metric/polish_e2.h) when its defect is at least
// the threshold; a flow stalled below kPolishableError counts as converged when the polish
// brings it under the tolerance.
void polish_lengths(const OneConeAtlasOptions& options, OneConeAtlasResult& result) {
  FlowResult& flow = result.flow;
  const bool stalled_at_floor = !flow.converged() && flow.status == FlowStatus::stalled &&
                                flow.lengths.size() > 0 && flow.max_error < kPolishableError;
  if (!flow.converged() && !stalled_at_floor) return;
  if (flow.max_error >= options.polish_threshold) {
    result.polish = polish_e2_lengths(result.problem.mesh, flow.lengths, result.problem.targets.curvature);
    flow.lengths = result.polish.lengths;
    result.polished = true;
  } else {
    result.polish.lengths = flow.lengths;
    result.polish.error_before = result.polish.error_after = flow.max_error;
  }
  if (stalled_at_floor && result.polish.error_after < options.flow.tolerance) {
    // The run's own failure record (the last one, naming its message) goes.
    auto& failed = flow.failed_attempts;
    if (!failed.empty() && failed.back().size() >= flow.message.size() &&
        failed.back().compare(failed.back().size() - flow.message.size(), flow.message.size(),
                              flow.message) == 0) {
      failed.pop_back();
    }
    flow.metric_name += ", stalled at the rounding floor and polished in long double";
    flow.status = FlowStatus::converged;
    flow.message.clear();
  }
}

// prepare_and_solve, then the long-double polish of its lengths (polish_lengths), timed: the
// layout multiplies the flow's leftover defect (~1e-12 on hard scans) by the loops it closes.
void solve_and_polish(InputSurface& input, const OneConeAtlasOptions& options,
                      OneConeAtlasResult& result, const std::function<void(const char*)>& report,
                      bool fall_back) {
  prepare_and_solve(input, options, result, report, fall_back);
  StageTimer polish;
  polish_lengths(options, result);
  result.timings.polish = polish.wall.seconds();
  result.timings.cpu_polish = polish.cpu.seconds();
}

// The edges of a closed mesh's faces as sorted undirected_edge_key's, each once (from the face
// whose halfedge runs from its smaller end).
std::vector<std::uint64_t> sorted_edge_keys(const Eigen::MatrixX3i& closed_faces) {
  std::vector<std::uint64_t> keys;
  keys.reserve(static_cast<size_t>(closed_faces.rows()) * 3 / 2);
  for (Eigen::Index f = 0; f < closed_faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = closed_faces(f, k), b = closed_faces(f, (k + 1) % 3);
      if (a < b) keys.push_back(undirected_edge_key(a, b));
    }
  }
  std::sort(keys.begin(), keys.end());
  return keys;
}

// How many edges of the flow's input (its closed faces) the flipped triangulation's tables
// lost (removed_edges, without the mesh).
int removed_edge_count(const Eigen::MatrixX3i& closed_faces, const MeshTables& flipped) {
  const std::vector<std::uint64_t> edges = sorted_edge_keys(closed_faces);
  std::vector<std::uint64_t> kept;
  kept.reserve(static_cast<size_t>(flipped.num_edges()));
  for (int e = 0; e < flipped.num_edges(); ++e) {
    kept.push_back(undirected_edge_key(flipped.edge_vertices(e, 0), flipped.edge_vertices(e, 1)));
  }
  std::sort(kept.begin(), kept.end());
  std::vector<std::uint64_t> removed;
  std::set_difference(edges.begin(), edges.end(), kept.begin(), kept.end(),
                      std::back_inserter(removed));
  return static_cast<int>(removed.size());
}

// Gauss-Seidel sweeps of problem_log_scale over the vertices the problem added.
constexpr int kWarmStartSweeps = 10;

// The choice's prediction (by input vertex) on the problem's vertices: an input vertex keeps
// its value, a vertex added by the valence modification or the cone refinement takes the mean
// of its neighbours that have one, in breadth-first order from the input's, then
// kWarmStartSweeps sweeps of the mean of all its neighbours.
Eigen::VectorXd problem_log_scale(const OneConeProblem& problem, const Eigen::VectorXd& input_u) {
  const Mesh& mesh = problem.mesh;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(mesh.n_vertices()));
  std::vector<char> known(mesh.n_vertices(), 0);
  std::vector<int> added;
  for (size_t v = 0; v < mesh.n_vertices(); ++v) {
    const int i = v < problem.input_vertex.size() ? problem.input_vertex[v] : -1;
    if (i >= 0 && i < input_u.size()) {
      u[static_cast<Eigen::Index>(v)] = input_u[i];
      known[v] = 1;
    } else {
      added.push_back(static_cast<int>(v));
    }
  }
  const std::vector<int> all_added = added;
  while (!added.empty()) {
    std::vector<int> left;
    std::vector<std::pair<int, double>> filled;
    for (int v : added) {
      double sum = 0.0;
      int count = 0;
      for (auto w : mesh.vv_range(mesh.vertex_handle(v))) {
        if (known[static_cast<size_t>(w.idx())]) {
          sum += u[w.idx()];
          ++count;
        }
      }
      if (count > 0) {
        filled.emplace_back(v, sum / count);
      } else {
        left.push_back(v);
      }
    }
    if (filled.empty()) break;  // a component without input vertices keeps 0
    for (const auto& [v, value] : filled) {
      u[v] = value;
      known[static_cast<size_t>(v)] = 1;
    }
    added = std::move(left);
  }
  // The added vertices sit next to the cone, where u bends like a logarithm: a few
  // Gauss-Seidel sweeps make them the harmonic extension of the input's values.
  for (int sweep = 0; sweep < kWarmStartSweeps; ++sweep) {
    for (int v : all_added) {
      double sum = 0.0;
      int count = 0;
      for (auto w : mesh.vv_range(mesh.vertex_handle(v))) {
        sum += u[w.idx()];
        ++count;
      }
      if (count > 0) u[v] = sum / count;
    }
  }
  return u;
}

bool intrinsic_applies(const OneConeProblem& problem) {
  return problem.kind == OneConeKind::SingleCone || problem.kind == OneConeKind::FlatTorus;
}

// The intrinsic Delaunay flow on the problem's mesh and targets. When it converges, the problem's
// mesh becomes its triangulation (vertices kept) and result.flow carries its figures and
// lengths; the failures of earlier flows stay listed in flow.failed_attempts.
void solve_intrinsic(const OneConeAtlasOptions& options, OneConeAtlasResult& result,
                     const std::function<void(const char*)>& report) {
  report("intrinsic Delaunay flow");
  StageTimer t;
  const std::size_t vertices = result.problem.targets.curvature.size();
  release_free_memory(vertices);  // the valence modification's, before the flow's factors
  IntrinsicFlowOptions settings = options.intrinsic;
  // The long-double polish below finishes the flow: Newton hands over at kPolishHandover,
  // where one polish step lands at the rounding floor (its quadratic term ~1e-19), and the
  // tolerance applies to the polished metric.
  const double tolerance = options.flow.tolerance;
  const bool polishes = std::isfinite(options.polish_threshold);
  settings.tolerance = polishes ? std::max(tolerance, kPolishHandover) : tolerance;
  settings.solver = options.flow.solver;
  settings.progress = options.flow.progress;
  if (static_cast<double>(result.problem.mesh.n_faces()) >= options.polish_floor_from_faces) {
    settings.floor_plateau_iterations = 0;
  }
  std::vector<std::string> failures = result.flow.failed_attempts;
  if (!result.flow.message.empty()) failures.push_back(result.flow.message);
  IntrinsicTriangulation initial = make_intrinsic_triangulation(
      result.problem.mesh, mesh_edge_lengths(result.problem.mesh));
  // (The record's copy: the flow takes `initial`, and its flip log numbers initial's edges.)
  IntrinsicTriangulation initial_copy =
      options.keep_flip_record ? initial : IntrinsicTriangulation();
  const bool warm = options.warm_start && result.predicted_log_scale.size() > 0 &&
                    result.problem.kind == OneConeKind::SingleCone &&
                    static_cast<double>(result.problem.mesh.n_faces()) < options.warm_start_below_faces;
  const Eigen::VectorXd warm_u =
      warm ? Eigen::VectorXd(options.warm_start_fraction *
                             problem_log_scale(result.problem, result.predicted_log_scale))
           : Eigen::VectorXd();
  // The problem's mesh waits as arrays (38 MB against OpenMesh's 136 at 1.6M faces, beside the
  // flow's factorisation) while the flow and the polish run; it comes back only if they fail.
  const VertexFaceArrays problem_mesh = to_arrays(result.problem.mesh);
  result.problem.mesh.clear();  // (assigning an empty Mesh keeps the arrays' capacity)
  IntrinsicFlowResult r =
      warm ? intrinsic_conformal_flow(std::move(initial), result.problem.targets.curvature,
                                      warm_u, settings)
           : intrinsic_conformal_flow(std::move(initial), result.problem.targets.curvature, settings);
  result.warm_start = r.warm_start;
  FlowResult flow = to_flow_result(r);
  flow.failed_attempts = failures;
  flow.linear_work += result.flow.linear_work;  // an earlier flow's, replaced here
  result.intrinsic_flips = r.flips;
  result.intrinsic_trials = r.line_search_trials;
  double polish_seconds = 0.0, polish_cpu = 0.0;
  // A flow stopped at its rounding floor is finished by the long-double polish.
  const bool near = r.converged() || r.max_error < settings.freeze_connectivity_below;
  if (near && !is_simplicial(r.triangulation)) {
    flow.status = FlowStatus::stalled;
    flow.message = "the intrinsic Delaunay triangulation has a loop or a double edge "
                   "(not supported by the atlas)";
  } else if (near) {
    // The polish runs on the triangulation's tables; its mesh (136 MB at 1.6M faces against
    // the tables' 61) is built after it, once the flow's factorisation is gone.
    const MeshTables tables = to_mesh_tables(r.triangulation);
    Eigen::VectorXd lengths = table_edge_lengths(r.triangulation, tables, r.u);
    r.triangulation = IntrinsicTriangulation();  // its tables (~90 MB at 1.6M faces) are done
    release_free_memory(vertices);  // and the flow's evaluations, before the polish's
    // As after the fixed-connectivity flows (polish_lengths): the layout multiplies the
    // leftover defect by the distances it spans, so it goes in long double first, whatever its
    // size: flips of slivers leave edges far shorter than the input's (femur: a defect of
    // 1.4e-13 gave 1e-9 relative error on its shortest edge).
    // The mesh and the removed edges need the connectivity only: below
    // mesh_beside_polish_below_faces they are built on a second thread beside the polish (and
    // thrown away if it fails), from there after it, once the factorisation is freed.
    const bool polish = !r.converged() || polishes;
    const bool beside = polish && static_cast<double>(tables.num_faces()) <
                                      options.mesh_beside_polish_below_faces;
    Mesh mesh;
    std::vector<int> edge_of;
    const auto build_mesh = [&] { mesh = mesh_of_tables(tables, problem_mesh.V, edge_of); };
    const auto count_removed = [&] {
      result.removed_edges = removed_edge_count(problem_mesh.F, tables);
    };
    // Beside the polish, the atlas' cut graph and slicing too (cut_beside_polish), held in
    // result.atlas until the atlas stage completes it: the cut graph's shortest paths on the
    // unpolished lengths, ~1e-12 from the polished ones.
    const auto cut_and_slice = [&] {
      try {
        result.atlas.cut = compute_cut_graph(mesh, atlas_root(result.problem, mesh),
                                             by_mesh_edge(Eigen::VectorXd(lengths), edge_of));
        result.atlas.sliced = slice_along(mesh, result.atlas.cut.is_cut_edge);
      } catch (const std::exception&) {
        result.atlas = AffineAtlas();  // the atlas stage makes them again and reports it
      }
    };
    if (polish) {
      report("long-double polish");
      run_workers(beside ? 2 : 1, [&](int worker) {
        if (worker == 1) {
          build_mesh();
          count_removed();
          if (options.cut_beside_polish) cut_and_slice();
          return;
        }
        const StageTimer timer;
        const NearbyLaplacian nearby{r.laplacian_factorization.get(), r.pinned_vertex};
        result.polish = polish_e2_lengths(tables, lengths, result.problem.targets.curvature, 6,
                                          nearby, kPolishGoal);
        polish_seconds = timer.wall.seconds();
        polish_cpu = timer.cpu.seconds();
      });
      result.polished = true;
      if (result.polish.error_after <= tolerance) {
        lengths = result.polish.lengths;
        flow.status = FlowStatus::converged;
        flow.message.clear();
        flow.max_error = result.polish.error_after;
      } else if (r.max_error > tolerance) {
        flow.status = FlowStatus::stalled;
        std::ostringstream message;
        message << "intrinsic conformal flow: the long-double polish left max |K - K̄| = "
                << result.polish.error_after << " above the tolerance " << tolerance;
        flow.message = message.str();
      }
    }
    r.laplacian_factorization.reset();
    const bool converged = flow.status == FlowStatus::converged;
    if (converged) release_free_memory(vertices);  // the factorisation, before the mesh
    if (!beside) {
      // The removed edges (after the factor: their sorted keys) are counted on a second
      // thread while the mesh is built.
      run_workers(2, [&](int worker) {
        if (worker == 1) {
          count_removed();
        } else if (converged) {
          build_mesh();
        }
      });
    }
    if (converged) {
      flow.metric_name = "intrinsic Delaunay flow (vertex scaling, " + std::to_string(r.flips) +
                         " flips)";
      result.problem.mesh = std::move(mesh);
      flow.lengths = by_mesh_edge(std::move(lengths), edge_of);
      result.polish.lengths = by_mesh_edge(std::move(result.polish.lengths), edge_of);
      result.polish.lengths_low = by_mesh_edge(std::move(result.polish.lengths_low), edge_of);
      result.intrinsic = true;
      if (options.keep_flip_record) {
        result.flip_record = {same_order_mesh(problem_mesh), std::move(initial_copy),
                              std::move(r.flip_log), r.u};
      }
    }
  }
  if (flow.status != FlowStatus::converged) {
    result.problem.mesh = same_order_mesh(problem_mesh);
    result.atlas = AffineAtlas();  // a cut made beside a failed polish
  }
  result.flow = std::move(flow);
  result.timings.polish += polish_seconds;
  result.timings.cpu_polish += polish_cpu;
  result.timings.flow += t.wall.seconds() - polish_seconds;
  result.timings.cpu_flow += t.cpu.seconds() - polish_cpu;
}

// Flows whose attempt was thrown away: their failures, seconds and linear work.
struct Discarded {
  std::vector<std::string> failures;
  double seconds = 0.0, cpu_seconds = 0.0;
  LinearWork work;

  // The attempt's flow and polish costs (its failures are the caller's to take).
  void add_costs(const OneConeAtlasResult& attempt) {
    seconds += attempt.timings.flow;
    cpu_seconds += attempt.timings.cpu_flow;
    work += attempt.flow.linear_work;
    work += attempt.polish.linear_work;
  }
  void add_costs(const Discarded& other) {
    seconds += other.seconds;
    cpu_seconds += other.cpu_seconds;
    work += other.work;
  }
};

// The intrinsic flow on a fresh copy of `result`'s problem: `result` becomes it when it
// converges; otherwise its failures and costs join `discarded`. Returns whether it ran (the
// problem suits it).
bool try_intrinsic(InputSurface& input, const OneConeAtlasOptions& options,
                   const std::function<void(const char*)>& report, OneConeAtlasResult& result,
                   Discarded& discarded) {
  OneConeAtlasResult attempt = result;
  prepare_problem(input, options, attempt, report);
  if (!intrinsic_applies(attempt.problem)) return false;
  attempt.flow.failed_attempts = discarded.failures;
  solve_intrinsic(options, attempt, report);
  if (attempt.flow.converged()) {
    result = std::move(attempt);
  } else {
    discarded.failures = attempt.flow.failed_attempts;
    discarded.failures.push_back(attempt.flow.message);
    discarded.add_costs(attempt);
  }
  return true;
}

// Whether `result`'s flow converged on the tangent circles (the combinatorial metric, last of
// one_cone_metric_order) where options let the intrinsic flow run instead
// (OneConeAtlasOptions::intrinsic_before_combinatorial).
bool took_combinatorial(const OneConeAtlasOptions& options, const OneConeAtlasResult& result) {
  if (!options.intrinsic_before_combinatorial || options.route != FlowRoute::automatic ||
      options.keep_metric || options.flow.geometry != Geometry::euclidean ||
      !options.cone_ring_metrics.empty() || !intrinsic_applies(result.problem)) {
    return false;
  }
  const auto order = one_cone_metric_order(result.problem.kind);
  const int position = metric_order_position(result.problem.kind, result.flow.metric_name);
  return position >= 0 && order[static_cast<std::size_t>(position)].first == Scheme::combinatorial;
}

// takes_intrinsic_flow_first, takes_inversive_distance_route and singularity_options on the
// mesh's surface_topology, computed once per build_one_cone_atlas (a pass over the mesh each).
bool intrinsic_first_on(const SurfaceTopology& topology, const OneConeAtlasOptions& options) {
  return options.intrinsic_first && options.route == FlowRoute::automatic &&
         !options.keep_metric && options.flow.geometry == Geometry::euclidean &&
         options.cone_ring_metrics.empty() && needs_singular_vertex(topology) &&
         topology.genus >= 2;
}

bool inversive_route_on(const SurfaceTopology& topology, const OneConeAtlasOptions& options) {
  const bool asked = !options.keep_metric || options.flow.scheme == Scheme::inversive_distance;
  return options.inversive_distance_route && asked &&
         options.flow.geometry == Geometry::euclidean && options.cone_ring_metrics.empty() &&
         needs_singular_vertex(topology) && topology.genus >= 2;
}

SingularityOptions singularity_options_on(const SurfaceTopology& topology,
                                          const OneConeAtlasOptions& options) {
  SingularityOptions choice = options.choice;
  choice.flow = options.flow;
  // Comparing distortions needs no more than 1e-8 (the verifying flows stop earlier).
  choice.flow.tolerance = std::max(options.flow.tolerance, options.choice.flow.tolerance);
  choice.valence = options.valence;
  // The plain inversive-distance flow the route replaces fails at most candidates of a
  // marching-cubes or CAD mesh: rank them with the default metrics instead.
  choice.keep_metric = options.keep_metric && !inversive_route_on(topology, options);
  return choice;
}

// The automatic singularity (choose_singularity; the linear model's best where only the
// intrinsic flow runs or no candidate converges with fixed connectivity): fills result's
// chosen vertex, choice figures and timings. Returns whether the fixed-connectivity flows
// failed at every candidate.
bool choose_vertex(InputSurface& input, const SurfaceTopology& topology,
                   const OneConeAtlasOptions& options, bool intrinsic_only,
                   OneConeAtlasResult& result) {
  StageTimer t;
  const Mesh& mesh = input.mesh();
  SingularityOptions choice = singularity_options_on(topology, options);
  // The problem's preparation checks every face's neighbourhood for thin handles (it needs no
  // cone): beside the model's factorisation.
  choice.beside_factorization = [&input, &mesh] {
    if (input.non_disk_faces().empty()) {
      input.set_non_disk_faces(non_disk_face_neighbourhoods(mesh));
    }
  };
  SingularityOptions with_prediction = choice;
  with_prediction.predict_log_scale = options.warm_start && intrinsic_first_on(topology, options) &&
                                      static_cast<double>(mesh.n_faces()) < options.warm_start_below_faces;
  bool fixed_failed = false;
  if (intrinsic_only) {
    result.chosen_vertex = rank_singularities(mesh, choice, &result.linear_work.choice).front().vertex;
  } else {
    try {
      SingularityChoice chosen = choose_singularity(mesh, with_prediction);
      result.chosen_vertex = chosen.vertex;
      result.predicted_log_scale = std::move(chosen.predicted_log_scale);
      result.flows_for_choice = chosen.flows_run;
      result.solves_for_choice = chosen.linear_solves;
      result.linear_work.choice = chosen.linear_work;
    } catch (const SolverError& error) {
      if (options.route == FlowRoute::fixed_connectivity) throw;
      // No candidate converged with fixed connectivity: the intrinsic flow converges at any
      // vertex; take the linear model's best.
      result.chosen_vertex =
          rank_singularities(mesh, choice, &result.linear_work.choice).front().vertex;
      result.flow.failed_attempts.push_back(error.what());
      fixed_failed = true;
    }
  }
  result.timings.choice = t.wall.seconds();
  result.timings.cpu_choice = t.cpu.seconds();
  return fixed_failed;
}

}  // namespace

OneConeAtlasOptions inversive_distance_route(const OneConeAtlasOptions& options) {
  OneConeAtlasOptions route = options;
  route.collapse_short_edges = true;
  route.short_edges.relative_length = 0.01;
  route.flip_flat_edges = true;
  route.flat_flips.max_normal_angle = 5.0 * M_PI / 180.0;
  route.flat_flips.max_relative_deviation = 0.01;
  // Asked for with its radii, else by default with the mean radii (more triangles survive).
  const RadiusInit radii = options.keep_metric ? options.flow.radii : RadiusInit::mean;
  ConeRingMetric rule{Scheme::inversive_distance, Scheme::circle_packing, 4, radii};
  rule.nonnegative_inversive_distance = true;
  route.cone_ring_metrics = {rule};
  route.continuation.stages = 4;
  return route;
}

bool takes_intrinsic_flow_first(const Mesh& mesh, const OneConeAtlasOptions& options) {
  return intrinsic_first_on(surface_topology(mesh), options);
}

bool takes_inversive_distance_route(const Mesh& mesh, const OneConeAtlasOptions& options) {
  return inversive_route_on(surface_topology(mesh), options);
}

double OneConeAtlasResult::relative_transition_residual() const {
  double residual = std::max(atlas.max_transition_residual, atlas.max_side_pairing_residual);
  return atlas.domain_diameter > 0 ? residual / atlas.domain_diameter : residual;
}

SingularityOptions singularity_options(const Mesh& mesh, const OneConeAtlasOptions& options) {
  return singularity_options_on(surface_topology(mesh), options);
}

namespace {

// build_one_cone_atlas on the input as held (the caller's mesh or one the pipeline owns).
OneConeAtlasResult build_atlas(InputSurface& input, const OneConeAtlasOptions& options) {
  const StageTimer start;
  const std::function<void(const char*)> report = [&](const char* stage) {
    if (options.progress) options.progress(stage);
  };
  OneConeAtlasResult result;
  result.chosen_vertex = options.singular_vertex;
  const SurfaceTopology topology = surface_topology(input.mesh());
  const std::size_t vertices = input.mesh().n_vertices();
  const bool needs_cone = needs_singular_vertex(topology);
  const bool intrinsic_only =
      options.route == FlowRoute::intrinsic_delaunay ||
      (options.route == FlowRoute::automatic && needs_cone &&
       topology.genus >= options.intrinsic_from_genus);
  bool fixed_failed = false;  // no candidate vertex converged with the fixed-connectivity flows
  bool intrinsic_tried = false;
  if (result.chosen_vertex < 0 && needs_cone) {
    release_free_memory(vertices);  // what reading the input freed, before the model's factor
    report("choosing the singular vertex");
    fixed_failed = choose_vertex(input, topology, options, intrinsic_only, result);
    release_free_memory(vertices);  // the linear model's factor and blocks, before the flow's
  }

  Discarded discarded;
  if (!intrinsic_only && !fixed_failed && intrinsic_first_on(topology, options)) {
    intrinsic_tried = try_intrinsic(input, options, report, result, discarded);
  }
  if (result.flow.converged()) {
    // The intrinsic flow ran first and won.
  } else if (intrinsic_only || fixed_failed) {
    prepare_problem(input, options, result, report);
    if (!intrinsic_applies(result.problem)) {
      throw InvalidInputError("the intrinsic Delaunay flow needs a closed surface of genus >= 1");
    }
    solve_intrinsic(options, result, report);
  } else if (inversive_route_on(topology, options)) {
    OneConeAtlasResult attempt = result;
    solve_and_polish(input, inversive_distance_route(options), attempt, report, false);
    if (attempt.flow.converged()) {
      result = std::move(attempt);
      result.flow.metric_name = "inversive-distance route (" + result.flow.metric_name + ")";
    } else {
      discarded.failures.insert(discarded.failures.end(), attempt.flow.failed_attempts.begin(),
                                attempt.flow.failed_attempts.end());
      discarded.add_costs(attempt);
      if (options.route == FlowRoute::automatic && options.intrinsic_before_fixed &&
          !intrinsic_tried) {
        // Next in conformality: the intrinsic flow (vertex scaling), before the circle packings.
        intrinsic_tried = try_intrinsic(input, options, report, result, discarded);
      }
      if (!result.flow.converged()) solve_and_polish(input, options, result, report, true);
    }
  } else {
    solve_and_polish(input, options, result, report, true);
  }
  if (result.flow.converged() && !intrinsic_tried && !result.intrinsic &&
      took_combinatorial(options, result)) {
    // Tangent circles ignore the mesh's shape (elk: area-weighted QC 2.28 against the intrinsic
    // flow's 1.46): the intrinsic flow comes before them, and they are kept only if it fails.
    const std::string set_aside =
        result.flow.metric_name + ": converged, set aside for the intrinsic Delaunay flow "
                                  "(tangent circles ignore the mesh's shape)";
    Discarded trial = discarded;
    trial.failures.insert(trial.failures.end(), result.flow.failed_attempts.begin(),
                          result.flow.failed_attempts.end());
    trial.failures.push_back(set_aside);
    const std::size_t listed_before = trial.failures.size();
    Discarded tangent_costs;
    tangent_costs.add_costs(result);
    // try_intrinsic replaces `result` only when the intrinsic flow converges.
    intrinsic_tried = try_intrinsic(input, options, report, result, trial);
    if (result.intrinsic) {
      trial.add_costs(tangent_costs);  // their failures are listed in the result's
      discarded = std::move(trial);
    } else {
      // The tangent circles stay: the intrinsic flow's failures are listed after theirs, its
      // costs counted with the discarded attempts'.
      std::vector<std::string>& listed = result.flow.failed_attempts;
      listed.insert(listed.end(),
                    trial.failures.begin() + static_cast<std::ptrdiff_t>(listed_before),
                    trial.failures.end());
      trial.failures = std::move(discarded.failures);
      discarded = std::move(trial);
    }
  }
  // The thrown-away attempts' failures come first, in the order they ran.
  if (!discarded.failures.empty()) {
    std::vector<std::string>& listed = result.flow.failed_attempts;
    std::vector<std::string> earlier;
    for (const std::string& f : discarded.failures) {
      if (std::find(listed.begin(), listed.end(), f) == listed.end()) earlier.push_back(f);
    }
    listed.insert(listed.begin(), earlier.begin(), earlier.end());
  }
  result.timings.flow += discarded.seconds;
  result.timings.cpu_flow += discarded.cpu_seconds;
  if (!result.flow.converged() && options.route == FlowRoute::automatic && !fixed_failed &&
      !intrinsic_tried && intrinsic_applies(result.problem)) {
    solve_intrinsic(options, result, report);
  }
  if (!result.flow.converged()) throw SolverError(result.flow.message);

  result.linear_work.flow = discarded.work;
  result.linear_work.flow += result.flow.linear_work;
  result.linear_work.polish = result.polish.linear_work;

  release_free_memory(vertices);  // the flow's and the polish's, before the layout's
  report("cut graph, layout and atlas; distortion");
  const StageTimer t;
  // The polish's long-double metric when the flow's lengths are its rounding.
  const bool long_metric = result.polished && result.polish.lengths_low.size() == result.flow.lengths.size() &&
                           result.polish.lengths == result.flow.lengths;
  // The flipped triangulation's faces are not the input's: one may be flat in 3D (three
  // vertices on a line), where the distortion is undefined; those are counted and left out.
  DistortionOptions measure;
  measure.skip_degenerate = result.intrinsic;
  // The cut graph and slicing made beside the intrinsic flow's polish, when they are there
  // (same mesh, same root).
  const bool cut_ready =
      result.intrinsic && result.atlas.sliced.mesh.n_faces() == result.problem.mesh.n_faces() &&
      result.atlas.sliced.mesh.n_faces() > 0 &&
      result.atlas.cut.is_cut_edge.size() == result.problem.mesh.n_edges() &&
      result.atlas.cut.root == atlas_root(result.problem, result.problem.mesh);
  // The distortion reads only the mesh and the metric: it is measured on a second thread
  // while the atlas (serial for the most part: cut graph, slicing, the layout's growth) is built.
  double distortion_seconds = 0.0;
  run_workers(2, [&](int worker) {
    if (worker == 1) {
      const Stopwatch clock;
      result.distortion = measure_distortion(result.problem.mesh, result.flow.lengths, measure);
      distortion_seconds = clock.seconds();
      return;
    }
    const Eigen::VectorXd low = long_metric ? result.polish.lengths_low : Eigen::VectorXd();
    if (cut_ready) {
      complete_affine_atlas(result.problem.mesh, result.flow.lengths, low, options.atlas,
                            result.atlas);
    } else {
      result.atlas = build_affine_atlas(result.problem.mesh, result.flow.lengths, low,
                                        atlas_root(result.problem, result.problem.mesh),
                                        options.atlas);
    }
  });
  result.timings.atlas = t.wall.seconds();
  result.timings.cpu_atlas = t.cpu.seconds();
  result.timings.distortion = distortion_seconds;
  result.timings.total = start.wall.seconds();
  result.timings.cpu_total = start.cpu.seconds();
  return result;
}

}  // namespace

OneConeAtlasResult build_one_cone_atlas(const Mesh& mesh, const OneConeAtlasOptions& options) {
  InputSurface input = InputSurface::kept(mesh);
  return build_atlas(input, options);
}

OneConeAtlasResult build_one_cone_atlas(Mesh&& mesh, const OneConeAtlasOptions& options) {
  InputSurface input = InputSurface::handed_over(mesh);
  return build_atlas(input, options);
}

}  // namespace ricci

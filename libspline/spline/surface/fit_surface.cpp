#include "spline/surface/fit_surface.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <unordered_set>
#include <utility>

#include "ricci/mesh/arrays.h"
#include "ricci/mesh/edge_statistics.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/simplify.h"
#include "ricci/mesh/small_holes.h"
#include "ricci/util/hash.h"
#include "ricci/util/stopwatch.h"
#include "spline/surface/adaptive_domain.h"
#include "spline/surface/cap_holes.h"
#include "spline/surface/fold_smoothing.h"
#include "spline/surface/tessellate_surface.h"
#include "spline/tessellate/parallel_for.h"

namespace spline {
namespace {

// Wall-clock and CPU seconds of consecutive stages: a stage ends when the next one begins.
class StageClock {
 public:
  StageClock(FittedSurface& out, const FitSurfaceOptions& options)
      : out_(out), progress_(options.progress) {}
  void begin(const std::string& name) {
    if (!stage_.empty()) {
      add(out_.seconds, stage_, stage_timer_.wall.seconds());
      add(out_.cpu_seconds, stage_, stage_timer_.cpu.seconds());
    }
    stage_timer_.restart();
    stage_ = name;
    if (progress_ && !name.empty()) progress_(name);
  }
  void finish() {
    begin("");
    out_.seconds.emplace_back("total", total_.wall.seconds());
    out_.cpu_seconds.emplace_back("total", total_.cpu.seconds());
  }

 private:
  // A stage run again (a refinement round) adds to its first entry.
  static void add(StageSeconds& stages, const std::string& name, double seconds) {
    for (auto& [stage, s] : stages) {
      if (stage == name) {
        s += seconds;
        return;
      }
    }
    stages.emplace_back(name, seconds);
  }

  FittedSurface& out_;
  const std::function<void(const std::string&)>& progress_;
  ricci::StageTimer total_, stage_timer_;
  std::string stage_;
};

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

// The caller's singular vertex (an index of the input) as a vertex of the domain mesh fit_scan
// will build: the simplification is deterministic, so running it here gives the same mesh.
int domain_singular_vertex(const ricci::Mesh& dense, const FitSurfaceOptions& options,
                           const std::optional<ricci::Mesh>& domain) {
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
  const Eigen::Vector3d point = ricci::to_eigen(dense.point(dense.vertex_handle(v)));
  if (domain) return nearest_interior_vertex(*domain, point);
  if (static_cast<int>(dense.n_faces()) <= options.domain_faces) return v;
  ricci::SimplifyOptions simplify;
  simplify.target_faces = options.domain_faces;
  const ricci::Mesh simplified = ricci::simplify_mesh(dense, simplify).mesh;
  return nearest_interior_vertex(simplified, point);
}

// The adaptive domain's cone, chosen as the atlas would (least area distortion), with its star
// split once (split_domain_faces, farthest placement): the cone goes where the surface is
// flattest, where the adaptive domain is coarsest, and its star is the hole the fill patch
// covers (genus 0) or the first ring of the charts.
int split_cone_star(const ricci::Mesh& dense, ScanFitOptions& scan) {
  ricci::Mesh& domain = *scan.domain;
  const int cone =
      ricci::choose_singularity(domain, ricci::singularity_options(domain, scan.atlas)).vertex;
  if (cone < 0) return -1;
  std::vector<char> star(domain.n_faces(), 0);
  for (auto f : domain.vf_range(domain.vertex_handle(cone))) star[static_cast<std::size_t>(f.idx())] = 1;
  domain = split_domain_faces(domain, dense, star, SplitPlacement::farthest_point);
  return cone;  // split_domain_faces keeps the old vertices' indices
}

void check_domain_size(const ricci::Mesh& dense, const ricci::SurfaceTopology& input,
                       const FitSurfaceOptions& options) {
  const int minimum = minimum_domain_faces(input.genus);
  const std::string genus = std::to_string(input.genus);
  if (options.domain_faces < minimum) {
    throw ricci::InvalidInputError("too few domain faces: " +
                                   std::to_string(options.domain_faces) + " for a genus-" + genus +
                                   " surface (at least " + std::to_string(minimum) + ")");
  }
  if (static_cast<int>(dense.n_faces()) < minimum) {
    throw ricci::InvalidInputError("the mesh has " + std::to_string(dense.n_faces()) +
                                   " faces, too few for a genus-" + genus +
                                   " spline domain (at least " + std::to_string(minimum) + ")");
  }
}

ScanFitOptions scan_options(const FitSurfaceOptions& options) {
  ScanFitOptions scan;
  scan.domain_faces = options.domain_faces;
  scan.degree = options.degree;
  scan.fair_r = options.fairness_order();
  scan.fit.smoothing = options.smoothing;
  scan.atlas.cone_refinement = options.cone_refinement;
  scan.tracked_parameters = options.tracked_parameters;
  return scan;
}

// Fold rounds: the raised smoothing (fold_smoothing_floor) grows by this factor each round;
// they stop after this many rounds in a row that fold no less (horse.ply: its first fit folds
// at 3 edges, every round at 5).
constexpr double kFoldSmoothingStep = 3.0;
constexpr int kFoldRoundsWithoutGain = 2;
// A fold round that leaves as many folds as the round it refits and moves the projection's RMS
// by less than this fraction of it is the last of its series (kept when better): the raised
// smoothing does not reach those folds, and more of it would not either (generated genus 8 at
// 12k faces: 3 folds by the cone's rim in ten rounds, each within 1e-7 of the last; the shared
// models' fold rounds that keep their folds move the RMS by 0.8% or more).
constexpr double kFoldRoundStall = 1e-4;
// A fold of the surface is "at the input's own folds" within this many median domain edges.
constexpr double kFoldNearInputFoldEdges = 2.0;
// The tapered series' FoldSmoothingOptions::taper_rings (run_fold_rounds).
constexpr int kFoldTaperRings = 3;

// An open input's refit without the boundary curve takes none of it within this many rings of
// the boundary (the collar included).
constexpr int kBoundaryBandRings = 2;

// Gauss-Newton steps of the projection: the distance is stationary in the parameter, so its
// error is second order in the step left (cup.off: 6 -> 2 steps moves the RMS by 0.07% of
// itself, the maximum not at all, for half the evaluations).
constexpr int kProjectionIterations = 2;

// Distance from `target` to the patch (Gauss-Newton in D from the nearest tessellation vertex),
// -1 when the patch has no interior vertex.
double distance_to_patch(const HoleFill& fill, const PatchTessellation& patch,
                         const Eigen::Vector3d& target) {
  if (patch.positions.rows() == 0) return -1.0;
  Eigen::Index nearest = 0;
  (patch.positions.rowwise() - target.transpose()).rowwise().squaredNorm().minCoeff(&nearest);
  Eigen::Vector2d u = patch.parameters.row(nearest).transpose();
  PatchPoint p = fill.evaluate(u);
  double best = (p.position - target).norm();
  double radius = 0.0;
  for (const auto& c : fill.corners) radius = std::max(radius, (c - fill.center).norm());
  for (int it = 0; it < kProjectionIterations; ++it) {
    Eigen::Matrix<double, 3, 2> j;
    j << p.du, p.dv;
    const Eigen::Matrix2d jtj = j.transpose() * j;
    if (!(std::abs(jtj.determinant()) > 1e-300)) break;
    const Eigen::Vector2d next = u - jtj.ldlt().solve(j.transpose() * (p.position - target));
    // Beyond D: the closest point is on the spline, which is measured there.
    if ((next - fill.center).norm() > radius) break;
    const PatchPoint trial = fill.evaluate(next);
    const double d = (trial.position - target).norm();
    if (!(d < best)) break;
    best = d;
    u = next;
    p = trial;
  }
  return best;
}

// Distance to the nearest patch, -1 when there is none.
double distance_to_fills(const SplineSurface& surface,
                         const std::vector<PatchTessellation>& patches,
                         const Eigen::Vector3d& target) {
  double best = -1.0;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const double d = distance_to_patch(surface.fills[i], patches[i], target);
    if (d >= 0 && (best < 0 || d < best)) best = d;
  }
  return best;
}

// Measures of a spline taken ahead, on `spline`: the projections of the input's vertices
// (measure_projection's; `distance` by input vertex, -1: not projected) and the normal jumps
// across its domain edges (measure_surface's, edge_normal_jumps_deg by edge; empty: none).
struct ProjectionsAhead {
  ManifoldSpline spline;
  std::vector<double> distance;
  std::vector<double> edge_jumps;
};

// The distance of every input vertex whose parameter lies on a face of `surface` not skipped to
// its spline (project_to_spline from the parameter), -1 for the others, on `threads` threads
// until `stop` says to stop (parallel_for_until; the vertices left are -1).
ProjectionsAhead project_ahead(const ricci::Mesh& dense, const std::vector<DomainPoint>& parameters,
                               const SplineSurface& surface, int threads,
                               const std::function<bool()>& stop) {
  ProjectionsAhead ahead{surface.spline, {}, {}};
  const Eigen::MatrixX3d points = ricci::vertex_positions(dense);
  ahead.distance.assign(static_cast<std::size_t>(points.rows()), -1.0);
  parallel_for_until(ahead.distance.size(), threads, stop, [&](std::size_t k) {
    const DomainPoint& start = parameters[k];
    if (start.face < 0 || surface.skipped_faces[static_cast<std::size_t>(start.face)] ||
        !surface.spline.space->in_domain(start.face))
      return;
    ahead.distance[k] = project_to_spline(surface.spline, start,
                                          points.row(static_cast<Eigen::Index>(k)).transpose(),
                                          kProjectionIterations)
                            .distance;
  });
  return ahead;
}

// By face: whether a projection starting there reads `a` and `b` alike. Each of its
// `steps` Gauss-Newton steps moves at most to a domain face across an edge
// (project_to_spline), so every domain face within `steps` such moves must evaluate alike.
std::vector<char> projections_alike(const ManifoldSpline& a, const ManifoldSpline& b, int steps) {
  const ManifoldSplineSpace& space = *a.space;
  std::vector<char> alike = faces_evaluated_alike(a, b);
  for (int step = 0; step < steps; ++step) {
    std::vector<char> next = alike;
    for (int f : space.domain_faces()) {
      for (int k = 0; k < 3; ++k) {
        const int g = space.neighbour(f, k);
        if (g >= 0 && space.in_domain(g) && !alike[static_cast<std::size_t>(g)])
          next[static_cast<std::size_t>(f)] = 0;
      }
    }
    alike = std::move(next);
  }
  return alike;
}

// Distances of the input's vertices to the exact surface: the spline by closest-point
// projection from their parameters; vertices whose parameter is outside the tessellated faces
// (the cone's star, a patch's covered faces) to the nearest patch. In parallel. A projection
// taken `ahead` on a spline that reads as this one where it runs (projections_alike) is kept.
// Returns the distance of every input vertex (-1: left out).
std::vector<double> measure_projection(const ricci::Mesh& dense,
                                       const std::vector<DomainPoint>& parameters,
                                       const std::vector<PatchTessellation>& patches,
                                       FittedSurface& out,
                                       const ProjectionsAhead* ahead = nullptr) {
  const SplineSurface& surface = out.surface;
  out.fit_points_on_fills = out.projection_points = 0;
  out.projection_max = 0.0;
  const Eigen::MatrixX3d points = ricci::vertex_positions(dense);
  std::vector<double> distance(static_cast<std::size_t>(points.rows()), -1.0);
  std::vector<char> on_fill(distance.size(), 0);
  if (ahead && (ahead->spline.space != surface.spline.space ||
                ahead->distance.size() != distance.size()))
    ahead = nullptr;
  const std::vector<char> kept =
      ahead ? projections_alike(ahead->spline, surface.spline, kProjectionIterations)
            : std::vector<char>{};
  parallel_for(distance.size(), 0, [&](std::size_t k) {
    const DomainPoint& start = parameters[k];
    const Eigen::Vector3d target = points.row(static_cast<Eigen::Index>(k)).transpose();
    if (start.face >= 0 && !surface.skipped_faces[static_cast<std::size_t>(start.face)]) {
      if (ahead && ahead->distance[k] >= 0 && kept[static_cast<std::size_t>(start.face)]) {
        distance[k] = ahead->distance[k];
        return;
      }
      distance[k] =
          project_to_spline(surface.spline, start, target, kProjectionIterations).distance;
      return;
    }
    distance[k] = distance_to_fills(surface, patches, target);
    on_fill[k] = distance[k] >= 0;
  });
  for (char c : on_fill) out.fit_points_on_fills += c;
  double sum = 0.0;
  for (double d : distance) {
    if (d < 0) continue;
    sum += d * d;
    out.projection_max = std::max(out.projection_max, d);
    ++out.projection_points;
  }
  out.projection_rms = out.projection_points > 0 ? std::sqrt(sum / out.projection_points) : 0.0;
  return distance;
}

// What the delivered surface is measured against: the input as given (fit_surface's `input`,
// its small holes not capped), the holes fit_surface capped in it, and the input prepared for
// measure_against_scan (prepared_input: begun on another thread while the first round is
// simplified).
struct DeliveredTarget {
  const ricci::Mesh& input;
  const ricci::SmallHoleCaps& holes;
  std::shared_future<std::shared_ptr<const PreparedScan>> prepared;
};

// The input's triangles and search tree for measure_against_scan, built on a thread of its own.
std::shared_future<std::shared_ptr<const PreparedScan>> prepared_input(const ricci::Mesh& input) {
  return std::async(std::launch::async, [&input] {
           const ricci::VertexFaceArrays arrays = ricci::to_arrays(input);
           std::vector<std::array<int, 3>> triangles(static_cast<std::size_t>(arrays.F.rows()));
           for (Eigen::Index f = 0; f < arrays.F.rows(); ++f)
             triangles[static_cast<std::size_t>(f)] = {arrays.F(f, 0), arrays.F(f, 1),
                                                       arrays.F(f, 2)};
           return std::make_shared<const PreparedScan>(arrays.V, std::move(triangles));
         })
      .share();
}

// A round's tessellation measured against the DeliveredTarget (measure_delivered's figures), or
// what that measure threw; the order-independent fingerprint of the tessellation it measured.
struct DeliveredMeasure {
  ScanDistanceReport report;
  std::exception_ptr error;
  std::size_t tessellation = 0;
};

// FNV-1a over the tessellation's positions, triangles and triangle faces: a DeliveredMeasure is
// taken only by the tessellation it measured.
std::size_t fingerprint(const Tessellation& t) {
  // By 8-byte words: a pass of a millisecond over a 100k scan's tessellation.
  ricci::Fnv1a h;
  h.add_words(t.positions.data(), sizeof(double) * static_cast<std::size_t>(t.positions.size()));
  h.add_words(t.triangles.data(), sizeof(t.triangles[0]) * t.triangles.size());
  h.add_words(t.triangle_face.data(), sizeof(int) * t.triangle_face.size());
  return static_cast<std::size_t>(h.value());
}

// The delivered surface (as a file holds it) against the whole input, both ways. The boundary
// loops capped as small holes are left out of the boundary comparison. Reads out.tessellation,
// out.surface.fills and out.input alone (finish_round runs it beside measure_surface).
// `known`: samples of the surface measured ahead against target.prepared (KnownSampleDistances).
DeliveredMeasure measure_against_input(const DeliveredTarget& target,
                                       const FitSurfaceOptions& options, const FittedSurface& out,
                                       const KnownSampleDistances* known = nullptr) {
  DeliveredMeasure result;
  result.tessellation = fingerprint(out.tessellation);
  try {
    const TriangleSoup soup = float_welded(out.tessellation);
    // Patches capping the input's own boundary loops cover what the scan does not have: they
    // are left out of the surface-to-scan direction (and counted there).
    ScanDistanceOptions measure = options.measure;
    measure.known_samples = known;
    if (target.holes.capped_loops > 0)
      measure.unmeasured_scan_boundary = target.holes.capped_vertex;
    const auto& fills = out.surface.fills;
    const auto& face = out.tessellation.triangle_face;
    measure.unmeasured_surface_triangles.assign(face.size(), 0);
    for (std::size_t t = 0; t < face.size(); ++t) {
      if (face[t] >= 0) continue;
      const auto& fill = fills[static_cast<std::size_t>(-1 - face[t])];
      measure.unmeasured_surface_triangles[t] =
          out.input.boundary_loops > 0 && fill.rim.kind == Rim::Kind::boundary;
    }
    result.report =
        measure_against_scan(soup.positions, soup.triangles, *target.prepared.get(), measure);
  } catch (...) {
    result.error = std::current_exception();
  }
  return result;
}

// The delivered round's measure against the input (`measured`, when finish_round took it for
// this tessellation; otherwise measured now) into `out`; the guard against points of the
// surface far from the input.
void measure_delivered(const DeliveredTarget& target, const FitSurfaceOptions& options,
                       const std::optional<DeliveredMeasure>& measured, FittedSurface& out) {
  const DeliveredMeasure measure =
      measured && measured->tessellation == fingerprint(out.tessellation)
          ? *measured
          : measure_against_input(target, options, out);
  if (measure.error) std::rethrow_exception(measure.error);
  out.delivered = measure.report;
  out.bbox_diagonal = out.delivered.bbox_diagonal;
  out.fit_rms = out.delivered.fit_rms;
  out.fit_max = out.delivered.fit_max;
  out.fit_points = out.delivered.scan_points;
  const double limit = options.max_surface_deviation * out.bbox_diagonal;
  if (options.max_surface_deviation > 0 && out.delivered.surface_to_scan_max > limit) {
    const Eigen::Vector3d& p = out.delivered.surface_to_scan_max_point;
    char where[160];
    std::snprintf(where, sizeof where, "(%.6g, %.6g, %.6g) lies %.3g%%", p.x(), p.y(), p.z(),
                  100.0 * out.delivered.surface_to_scan_max / out.bbox_diagonal);
    throw ricci::SolverError("fit_surface: the surface point " + std::string(where) +
                             " of the bounding-box diagonal from the input (limit " +
                             std::to_string(100.0 * options.max_surface_deviation) +
                             "%): a spike or a sheet sticking out; nothing is delivered");
  }
}

// Samples per domain edge of measure_surface's seam normal jumps.
constexpr int kSeamSamplesPerEdge = 1;

// Topology and smoothness of the tessellation and the spline's own seams.
// `folds_only`: the dihedral angles alone (a round judged before its holes are capped, whose
// topology and seams are measured again once it is delivered).
// The rims left open on purpose: each is one boundary loop of the result (nearby input loops
// merged into one rim count once).
int expected_boundary_loops(const FittedSurface& out) {
  return static_cast<int>(out.surface.open_rims.size() - out.fill_failures.size());
}

// `ahead`: the seams' jumps measured on the spline before it was capped (ProjectionsAhead).
void measure_surface(FittedSurface& out, bool folds_only,
                     const ProjectionsAhead* ahead = nullptr) {
  const Tessellation& t = out.tessellation;
  if (folds_only) {
    out.surface_dihedral = dihedral_angles(t.triangles, t.positions);
    return;
  }
  // Independent measures of the tessellation, two at once.
  run_workers(2, [&](int worker) {
    if (worker == 0) {
      out.topology = check_watertight(t.triangles, t.positions);
      out.surface_dihedral = dihedral_angles(t.triangles, t.positions);
    } else {
      out.float_topology = float_welded_topology(t);
    }
  });
  const int expected_loops = expected_boundary_loops(out);
  out.watertight = out.topology.matches(out.input.genus, expected_loops) &&
                   out.float_topology.matches(out.input.genus, expected_loops);
  const ManifoldSpline& spline = out.surface.spline;
  const bool known = ahead && ahead->spline.space == spline.space && !ahead->edge_jumps.empty();
  out.edge_normal_jump_deg = max_edge_normal_jump_deg(
      spline, out.surface.domain, kSeamSamplesPerEdge, 0, out.surface.skipped_faces,
      known ? ahead->edge_jumps : std::vector<double>{},
      known ? faces_evaluated_alike(ahead->spline, spline) : std::vector<char>{});
}

// fit_scan's result split: the spline and its domain into the surface, the atlas kept.
void take_scan(ScanFitResult&& scan, FittedSurface& out) {
  out.atlas = std::move(scan.atlas);
  out.puncture = std::move(scan.puncture);
  const auto& problem = out.atlas.problem;
  out.surface.domain = problem.mesh;
  out.surface.spline = std::move(scan.spline);
  out.surface.singular_vertex = problem.cone;
  out.fit_constraint_residual = scan.fit.max_constraint_residual;
  out.fit_unconstrained_faces = scan.unconstrained_faces;
  out.collar_faces = std::move(scan.collar_faces);
  out.collar_refused = std::move(scan.collar_refused);
  out.boundary_follow = scan.boundary_follow;
}

// A round judged on the uniform grid whose folds all go when the grid is refined where it turns
// sharply (a tightly curved tip sampled too coarsely, not a fold of the spline) is judged on the
// refined grid: no fold. Otherwise the uniform grid's count stands, so that rounds compare.
void take_refined_if_unfolded(const FitSurfaceOptions& options, FittedSurface& out) {
  Tessellation refined = out.tessellation;
  refine_sharp_turns(refined, out.surface.spline, options.density_refine_turn_deg,
                     options.density_refine_levels);
  DihedralReport dihedral = dihedral_angles(refined.triangles, refined.positions);
  if (dihedral.over_90_deg > 0) return;
  out.tessellation = std::move(refined);
  out.surface_dihedral = std::move(dihedral);
}

struct EarlyCaps;

// What one fit round leaves for the refinement: the domain it was built on, the parameters of
// the input's vertices and the distance of every input vertex to the surface (-1: not measured).
struct Round {
  ricci::Mesh domain;
  std::vector<DomainPoint> parameters;
  std::vector<double> vertex_distance;
  Eigen::MatrixX3d data_points;  // fit_scan's, for a refit on the same space
  std::vector<DomainPoint> data_parameters;
  std::vector<DomainPoint> setup_parameters;  // fit_scan's, for the refit's thin-plate weights
  // By data point: its parameter pinned on the boundary curve (fit_scan's boundary samples and
  // the input's boundary vertices on it), kept by a refit's corrections.
  std::vector<char> pinned;
  FitOptions fit;
  double fit_rms_at_parameters = 0.0;  // fit_scan's FitResult::rms_at_parameters
  EarlyCaps* early_caps = nullptr;     // fit_surface's, when this round began one
  ManifoldSpline tessellated;  // the spline the surface's tessellation was sampled on
  // Its capped tessellation measured against the input (finish_round), for measure_delivered.
  std::optional<DeliveredMeasure> delivered;
};

// How finish_round treats the holes: rims left open (a round judged), capped cheaply
// (CapHolesOptions::screening: a round ranked for delivery) or capped (the round delivered).
enum class Caps { open, screened, full };

// cap_holes' options for out.surface as fit_surface caps it.
CapHolesOptions cap_options(const FitSurfaceOptions& options, const FittedSurface& out,
                            Caps caps) {
  CapHolesOptions cap;
  cap.open_input = out.input.boundary_loops > 0;
  cap.fill_boundaries = options.fill_boundaries;
  cap.collar_faces = out.collar_faces;
  cap.cone_hole = cone_hole_limits(out.input.genus, out.fit_unconstrained_faces > 0);
  cap.make_patches = caps != Caps::open;
  cap.screening = caps == Caps::screened;
  return cap;
}

// The full capping of the first round's surface, begun on a second thread as soon as its spline
// is fitted, while the main thread judges the round on its open rims (rims, tessellation,
// folds): that round is most often the one delivered, and the capping's serial stretches (the
// cone patch's ordering, factorisation and solves, meet_patches) leave the other core to the
// judging. cap_holes depends on the surface and its options alone, so the round delivered with
// the same spline takes this result, the one its own capping would give; any other round caps
// as before (the work here is lost). fit_surface waits for it before any refit, or cancels it
// when the round folds (it is then seldom the one delivered; if it is, its capping is made
// again). The wait was first for the bits: the patch's factorisation could take OpenBLAS'
// second thread, whose count is the process' (serial_blas.h). Every factorisation of the
// library now runs on one BLAS thread, so today the wait only keeps the two off each other's
// cores.
struct EarlyCaps {
  std::shared_ptr<const ManifoldSplineSpace> space;
  Eigen::MatrixX3d control_points;  // the spline capped
  std::vector<char> collar_faces;
  std::atomic<bool> stop{false};  // CapHolesOptions::cancel of the capping
  std::future<std::pair<SplineSurface, CapHolesReport>> capped;

  EarlyCaps() = default;
  EarlyCaps(const EarlyCaps&) = delete;
  EarlyCaps& operator=(const EarlyCaps&) = delete;
  // A capping still running when fit_surface returns or throws is no longer wanted: it stops
  // at its next check, and `capped` joins it.
  ~EarlyCaps() { stop = true; }

  void start(const FitSurfaceOptions& options, const FittedSurface& out) {
    space = out.surface.spline.space;
    control_points = out.surface.spline.control_points;
    collar_faces = out.collar_faces;
    SplineSurface surface = out.surface;
    surface.fills.clear();  // as deliver_round leaves them
    surface.open_rims.clear();
    CapHolesOptions cap = cap_options(options, out, Caps::full);
    cap.cancel = &stop;
    capped = std::async(std::launch::async, [surface = std::move(surface), cap]() mutable {
      CapHolesReport report = cap_holes(surface, cap);
      return std::make_pair(std::move(surface), std::move(report));
    });
  }

  // Blocks until the capping is done (its result kept for take).
  void wait() const {
    if (capped.valid()) capped.wait();
  }

  // Stops the capping at its next check and waits for it to end. take() then caps nothing,
  // unless the capping had already finished.
  void cancel() {
    stop = true;
    wait();
  }

  // Whether the capping begun here (and not taken yet) is the one of `out.surface`.
  [[nodiscard]] bool holds(const FittedSurface& out) const {
    const ManifoldSpline& spline = out.surface.spline;
    return capped.valid() && spline.space == space && out.collar_faces == collar_faces &&
           spline.control_points.rows() == control_points.rows() &&
           (spline.control_points.array() == control_points.array()).all();
  }

  // Whether the capping still runs.
  [[nodiscard]] bool running() const {
    return capped.valid() &&
           capped.wait_for(std::chrono::seconds(0)) != std::future_status::ready;
  }

  // The capping of `out.surface` if it was begun here (once) and not cancelled, else nothing.
  std::optional<CapHolesReport> take(FittedSurface& out) {
    if (!holds(out)) {
      wait();
      return std::nullopt;
    }
    try {
      auto [surface, report] = capped.get();
      out.surface = std::move(surface);
      return std::move(report);
    } catch (const ricci::Cancelled&) {
      return std::nullopt;
    }
  }
};

// What finish_round measures of the delivered round while its capping runs (EarlyCaps), on the
// surface before the capping: the capping moves only the control points next to the rims
// (meet_patches) and adds the patches, so most of these are the capped surface's measures,
// taken where they read the spline alike (projections_alike, the samples by their points).
struct MeasuredAhead {
  ProjectionsAhead projections;
  std::optional<KnownSampleDistances> samples;  // of `earlier`, against the input
};

// MeasuredAhead of out.surface (its holes still open) and of its tessellation `earlier`, on the
// calling thread alone (the capping's own threads keep the cores they use) until `stop` says
// the capping is done. The samples are left out when the input's search tree failed
// (measure_against_input reports it).
MeasuredAhead measure_ahead(const ricci::Mesh& dense, const DeliveredTarget& target,
                            const Round& round, const Tessellation& earlier,
                            const FittedSurface& out, const std::function<bool()>& stop) {
  MeasuredAhead ahead{project_ahead(dense, round.parameters, out.surface, 1, stop),
                      std::nullopt};
  if (!stop())
    ahead.projections.edge_jumps =
        edge_normal_jumps_deg(out.surface.spline, out.surface.domain, kSeamSamplesPerEdge, 1);
  if (earlier.triangles.empty() || stop()) return ahead;
  try {
    const TriangleSoup soup = float_welded(earlier);
    ahead.samples.emplace(soup.positions, soup.triangles, *target.prepared.get(), 1, stop);
  } catch (const std::exception&) {
    ahead.samples.reset();
  }
  return ahead;
}

// The holes of out.surface (its spline as fit_scan left it) found and capped as `caps` says;
// the tessellation (at `density`, 0: by domain size) and the measures of the surface itself.
// With open rims the vertices over them are left out of the projection: rounds judged that way
// compare with each other, and only the delivered one is capped. With `target` (a round capped
// in full) the tessellation is also measured against the input, into round.delivered.
void finish_round(const ricci::Mesh& dense, const FitSurfaceOptions& options, int density,
                  Caps caps, bool project, StageClock& clock, Round& round, FittedSurface& out,
                  const DeliveredTarget* target = nullptr) {
  const bool patches = caps != Caps::open;
  clock.begin(caps == Caps::full ? "fill" : caps == Caps::screened ? "screen" : "rims");
  const Tessellation earlier = std::move(out.tessellation);
  std::optional<CapHolesReport> early;
  std::optional<MeasuredAhead> ahead;
  if (caps == Caps::full && round.early_caps) {
    // The capping's wait used for the measures that do not need its patches.
    if (target && project && round.early_caps->holds(out) && round.early_caps->running())
      ahead = measure_ahead(dense, *target, round, earlier, out,
                            [&capping = *round.early_caps] { return !capping.running(); });
    early = round.early_caps->take(out);
  }
  CapHolesReport capped =
      early ? std::move(*early) : cap_holes(out.surface, cap_options(options, out, caps));
  out.fill_failures = std::move(capped.failures);
  out.boundary_rims = capped.boundary_rims;
  out.fallback_fills = capped.fallback_fills;
  out.fill_normal_jump_deg = capped.max_normal_jump_deg;
  out.fill_position_gap = capped.max_position_gap;

  clock.begin("tessellate");
  TessellationOptions tess;
  tess.density = density > 0                ? density
                 : options.density > 0      ? options.density
                                            : default_density(
                                             out.surface.spline.space->domain_face_count());
  // Rounds are judged on the uniform grid, where a fold's edges do not multiply with the
  // refinement; the delivered surface is refined where the grid turns sharply.
  tess.refine_levels = patches ? options.density_refine_levels : 0;
  tess.refine_turn_deg = options.density_refine_turn_deg;
  // The samples of the round's earlier tessellation on the faces the capping left alike.
  if (round.tessellated.space == out.surface.spline.space && earlier.density == tess.density) {
    tess.reuse = &earlier;
    tess.reuse_faces = faces_evaluated_alike(round.tessellated, out.surface.spline);
  }
  std::vector<PatchTessellation> tessellated_patches;
  out.tessellation = tessellate_surface(out.surface, tess, tessellated_patches);
  round.tessellated = out.surface.spline;

  clock.begin("measure");
  round.delivered.reset();
  const auto measure_round = [&] {
    measure_surface(out, !patches, ahead ? &ahead->projections : nullptr);
    if (!patches && out.surface_dihedral.over_90_deg > 0 && options.density_refine_levels > 0)
      take_refined_if_unfolded(options, out);
    if (project)
      round.vertex_distance = measure_projection(dense, round.parameters, tessellated_patches,
                                                 out, ahead ? &ahead->projections : nullptr);
  };
  if (!target || caps != Caps::full) {
    measure_round();
    return;
  }
  // Measured against the input beside the surface's own measures (patches: the tessellation
  // stays): the round is most often the one delivered (fit_surface's last stage takes this
  // measure then, Round::delivered). Both read the tessellation and write other fields of `out`.
  run_workers(2, [&](int worker) {
    if (worker == 1) {
      round.delivered = measure_against_input(
          *target, options, out, ahead && ahead->samples ? &*ahead->samples : nullptr);
      return;
    }
    measure_round();
  });
}

// One whole fit: fit_scan, then finish_round without patches (fit_surface caps the delivered
// round once, deliver_round); `project`: with the projection's measures. With `early_caps`
// the full capping begins beside finish_round (EarlyCaps).
Round fit_round(const ricci::Mesh& dense, const ScanFitOptions& scan,
                const FitSurfaceOptions& options, int density, bool project, StageClock& clock,
                FittedSurface& out, EarlyCaps* early_caps = nullptr) {
  ScanFitResult fitted = fit_scan(dense, scan);
  Round round;
  round.parameters = std::move(fitted.vertex_parameters);
  round.domain = std::move(fitted.domain);
  round.data_points = std::move(fitted.data_points);
  round.data_parameters = std::move(fitted.data_parameters);
  round.setup_parameters = std::move(fitted.setup_parameters);
  round.pinned.assign(round.data_parameters.size(), 0);
  for (std::size_t k = static_cast<std::size_t>(std::max(0, fitted.scan_data_points));
       k < round.pinned.size(); ++k)
    round.pinned[k] = 1;
  for (int v : fitted.pinned_scan_vertices) round.pinned[static_cast<std::size_t>(v)] = 1;
  round.fit = std::move(fitted.fit_options);
  round.fit_rms_at_parameters = fitted.fit.rms_at_parameters;
  take_scan(std::move(fitted), out);
  if (early_caps) {
    early_caps->start(options, out);
    round.early_caps = early_caps;
  }
  finish_round(dense, options, density, Caps::open, project, clock, round, out);
  return round;
}

// The projection's measures of a round fitted without them (fit_round's `project`).
void project_round(const ricci::Mesh& dense, StageClock& clock, Round& round,
                   FittedSurface& out) {
  clock.begin("measure");
  round.vertex_distance = measure_projection(dense, round.parameters, {}, out);
}

// The delivered round capped (`caps`: Caps::full, or Caps::screened to rank it): its holes
// filled (the spline moved to meet the patches), tessellated and measured again.
void deliver_round(const ricci::Mesh& dense, const DeliveredTarget& target,
                   const FitSurfaceOptions& options, Round& best, StageClock& clock,
                   FittedSurface& out, Caps caps = Caps::full) {
  out.surface.fills.clear();
  out.surface.open_rims.clear();
  finish_round(dense, options, out.tessellation.density, caps, true, clock, best, out, &target);
}

// A fit round after the first one, on scan.domain, into a surface of the same input.
std::pair<FittedSurface, Round> next_round(const ricci::Mesh& dense, const ScanFitOptions& scan,
                                           const FitSurfaceOptions& options, StageClock& clock,
                                           const FittedSurface& out) {
  FittedSurface next;
  next.input = out.input;
  next.bbox_diagonal = out.bbox_diagonal;
  Round round = fit_round(dense, scan, options, out.tessellation.density, true, clock, next);
  return {std::move(next), std::move(round)};
}

// An open input's fold round also corrects the parameters on the faces where its first refit
// moved a control point by more than this share of the projection RMS before it: a whole fit
// (fit_scan, which these rounds ran before) corrects them all, and with the smoothed faces'
// alone the open bunny refined twice (1.1M faces) ended with its surface 0.94% of the
// diagonal from the scan at an ear (0.85% by whole fits; 0.83% with these corrected too, 5% of
// its points).
constexpr double kMovedShareOfRms = 0.1;

// `flags` into `into` (grown to its size): set where either is.
void merge_flags(const std::vector<char>& flags, std::vector<char>& into) {
  into.resize(std::max(into.size(), flags.size()), 0);
  for (std::size_t f = 0; f < flags.size(); ++f) into[f] |= flags[f];
}

// The data points whose parameter lies on a face flagged in `faces` moved to their closest
// points on `spline` (correct_parameters, ScanFitOptions' correction steps), the pinned ones
// (Round::pinned) left on the boundary curve. Returns whether any point was moved.
bool correct_parameters_on(const ManifoldSpline& spline, const std::vector<char>& faces,
                           Round& round) {
  std::vector<std::size_t> which;
  for (std::size_t k = 0; k < round.data_parameters.size(); ++k) {
    const int face = round.data_parameters[k].face;
    if (k < round.pinned.size() && round.pinned[k]) continue;
    if (face >= 0 && static_cast<std::size_t>(face) < faces.size() &&
        faces[static_cast<std::size_t>(face)])
      which.push_back(k);
  }
  if (which.empty()) return false;
  std::vector<DomainPoint> parameters(which.size());
  Eigen::MatrixX3d points(static_cast<Eigen::Index>(which.size()), 3);
  for (std::size_t i = 0; i < which.size(); ++i) {
    parameters[i] = round.data_parameters[which[i]];
    points.row(static_cast<Eigen::Index>(i)) =
        round.data_points.row(static_cast<Eigen::Index>(which[i]));
  }
  const ScanFitOptions scan_defaults;
  const CorrectedParameters corrected =
      correct_parameters(spline, parameters, points, scan_defaults.correction_iterations,
                         round.fit.threads);
  for (std::size_t i = 0; i < which.size(); ++i)
    round.data_parameters[which[i]] = corrected.parameters[i];
  return true;
}

// A fold round: out's spline fitted again on its own space (the same domain, atlas and
// parameters as `best`), each face smoothed at least face_smoothing[f], the parameters on those
// faces corrected and the fit run again; measured as fit_round measures. No atlas, space or
// parameters of the whole scan are computed again. The thin-plate weights are set up from
// fit_scan's setup parameters, as its own fit's were: with the corrected parameters instead, the
// faces sparse_smoothing raises change all over the surface, and a refit without any floor
// moved armadillo.obj's control points by up to 0.6% of the diagonal (1e-9 with them), folding
// faces 12 rings from any fold it was meant to remove.
std::pair<FittedSurface, Round> refit_round(const ricci::Mesh& dense,
                                            const FitSurfaceOptions& options,
                                            const std::vector<double>& face_smoothing,
                                            const Round& best, StageClock& clock,
                                            const FittedSurface& out) {
  clock.begin("fit");
  FittedSurface next;
  next.input = out.input;
  next.bbox_diagonal = out.bbox_diagonal;
  next.atlas = out.atlas;
  next.surface.domain = out.surface.domain;
  next.surface.singular_vertex = out.surface.singular_vertex;
  next.collar_faces = out.collar_faces;
  next.collar_refused = out.collar_refused;
  next.boundary_follow = out.boundary_follow;
  next.fit_unconstrained_faces = out.fit_unconstrained_faces;
  const auto& space = out.surface.spline.space;
  FitOptions fit = best.fit;
  fit.face_smoothing = face_smoothing;
  const Eigen::MatrixX3d initial = piecewise_linear_control_points(*space, next.surface.domain);
  Round round;
  round.domain = best.domain;
  round.data_points = best.data_points;
  round.data_parameters = best.data_parameters;
  round.setup_parameters = best.setup_parameters;
  round.pinned = best.pinned;
  round.fit = best.fit;
  FitResult refit = fit_control_points(*space, round.setup_parameters, round.data_parameters,
                                       round.data_points, initial, fit);
  next.surface.spline.space = space;
  next.surface.spline.control_points = refit.control_points;
  // The parameter correction (as fit_scan's) of the points on the faces smoothed more, where
  // the surface moved (on open inputs also where the refit moved it: kMovedShareOfRms), then
  // the fit again: without it the foot points' error adds to the RMS.
  std::vector<char> corrected(face_smoothing.size(), 0);
  for (std::size_t f = 0; f < face_smoothing.size(); ++f) corrected[f] = face_smoothing[f] > 0.0;
  if (out.input.boundary_loops > 0) {
    merge_flags(faces_moved_farther(out.surface.spline, next.surface.spline,
                                    kMovedShareOfRms * out.projection_rms),
                corrected);
  }
  if (correct_parameters_on(next.surface.spline, corrected, round)) {
    refit = fit_control_points(*space, round.setup_parameters, round.data_parameters,
                               round.data_points, initial, fit);
    next.surface.spline.control_points = refit.control_points;
  }
  next.fit_constraint_residual = refit.max_constraint_residual;
  round.parameters.assign(round.data_parameters.begin(),
                          round.data_parameters.begin() +
                              static_cast<std::ptrdiff_t>(best.parameters.size()));
  finish_round(dense, options, out.tessellation.density, Caps::open, true, clock, round, next);
  return {std::move(next), std::move(round)};
}

// Rounds a better one replaced, latest last: the rounds are judged with their holes open, so
// deliver_best_round falls back on them when capping the holes makes the delivered one fold.
using Superseded = std::vector<std::pair<FittedSurface, Round>>;

// The stage times and the history of rounds of `from` moved to `to` (the surface delivered
// changes, the clock and the history go on).
void take_history(FittedSurface& to, FittedSurface& from) {
  to.seconds = std::move(from.seconds);
  to.cpu_seconds = std::move(from.cpu_seconds);
  to.refinement = std::move(from.refinement);
}

// Delivers `next` (and its round) instead of `out`, keeping out's stage times and history and
// what follow_boundary did (the later rounds reuse the first round's followed domain); the
// replaced round goes to `superseded` when given.
void adopt_round(std::pair<FittedSurface, Round>&& next, FittedSurface& out, Round& best,
                 Superseded* superseded = nullptr) {
  next.first.boundary_follow = out.boundary_follow;
  take_history(next.first, out);
  if (superseded) superseded->emplace_back(std::move(out), std::move(best));
  out = std::move(next.first);
  best = std::move(next.second);
}

// A fit's state between rounds: the surface delivered so far, its round, the rounds it replaced.
struct Attempt {
  FittedSurface out;
  Round round;
  Superseded superseded;
};

// The fold-free round the fold rounds' RMS limits refused with the lowest RMS within
// FitSurfaceOptions::fold_free_rms, if any: delivered rather than a round that folds.
using FoldFree = std::optional<std::pair<FittedSurface, Round>>;

bool within_fold_free_rms(const FittedSurface& s, const FitSurfaceOptions& options) {
  return s.surface_dihedral.over_90_deg == 0 &&
         s.projection_rms <= options.fold_free_rms * s.bbox_diagonal;
}

// `next` (a refused round) into `fold_free` when it does not fold and is within the RMS, with a
// lower RMS than the round kept there.
void keep_if_fold_free(std::pair<FittedSurface, Round>&& next, const FitSurfaceOptions& options,
                       FoldFree& fold_free) {
  if (!within_fold_free_rms(next.first, options)) return;
  if (fold_free && !(next.first.projection_rms < fold_free->first.projection_rms)) return;
  fold_free = std::move(next);
}

// `out`, delivered (capped), folds: the fold-free round kept aside is capped in turn and
// delivered instead when capped it still does not fold and stays within the RMS.
void deliver_fold_free(const ricci::Mesh& dense, const DeliveredTarget& target,
                       const FitSurfaceOptions& options, FoldFree& fold_free, Round& best,
                       StageClock& clock, FittedSurface& out) {
  if (!fold_free || out.surface_dihedral.over_90_deg == 0) return;
  deliver_round(dense, target, options, fold_free->second, clock, fold_free->first);
  if (within_fold_free_rms(fold_free->first, options))
    adopt_round(std::move(*fold_free), out, best);
  fold_free.reset();
}

// The largest normal jump across the spline's seams and the patches' rims, in degrees.
double seam_jump_deg(const FittedSurface& s) {
  return std::max(s.edge_normal_jump_deg, s.fill_normal_jump_deg);
}

// A seam this smooth or smoother is G1 to the eye (the fit's seam criterion).
constexpr double kSeamGoalDeg = 1.0;

// Capped `candidate` replaces capped `delivered` when it folds less, or as little with seams
// under kSeamGoalDeg where delivered's are not.
bool capped_better(const FittedSurface& candidate, const FittedSurface& delivered) {
  const int folds = candidate.surface_dihedral.over_90_deg;
  const int delivered_folds = delivered.surface_dihedral.over_90_deg;
  const bool smoother =
      seam_jump_deg(candidate) < kSeamGoalDeg && seam_jump_deg(delivered) >= kSeamGoalDeg;
  return folds < delivered_folds || (folds == delivered_folds && smoother);
}

// The round of `superseded` (latest first) whose capped surface beats `delivered`
// (capped_better), each one against the winner so far, capped as `caps` says; they stop once
// the winner folds no more than `judged` with seams under the goal. Null when none beats it.
std::pair<FittedSurface, Round>* best_capped(const ricci::Mesh& dense,
                                             const DeliveredTarget& target,
                                             const FitSurfaceOptions& options, Caps caps,
                                             int judged, const FittedSurface& delivered,
                                             Superseded& superseded, StageClock& clock) {
  std::pair<FittedSurface, Round>* winner = nullptr;
  for (auto it = superseded.rbegin(); it != superseded.rend(); ++it) {
    const FittedSurface& bar = winner ? winner->first : delivered;
    if (bar.surface_dihedral.over_90_deg <= judged && seam_jump_deg(bar) < kSeamGoalDeg) break;
    deliver_round(dense, target, options, it->second, clock, it->first, caps);
    if (capped_better(it->first, bar)) winner = &*it;
  }
  return winner;
}

// deliver_round on `best`; when the capped surface folds more than it did with its holes open,
// or its seams reach kSeamGoalDeg, the superseded rounds (latest first) are capped too and the
// one that folds least (then with seams under the goal) is delivered. Where a capping retries
// the cone hole (retries_cone_hole: 4-6 patches, where the screening makes one) the superseded
// rounds are ranked by the screening capping and only the winner is capped in full, delivered
// when it still beats `best`'s capping.
void deliver_best_round(const ricci::Mesh& dense, const DeliveredTarget& target,
                        const FitSurfaceOptions& options, Superseded& superseded, Round& best,
                        StageClock& clock, FittedSurface& out) {
  const int judged = out.surface_dihedral.over_90_deg;
  deliver_round(dense, target, options, best, clock, out);
  const bool screen =
      retries_cone_hole(cone_hole_limits(out.input.genus, out.fit_unconstrained_faces > 0));
  // The spline as fitted, before a screening capping moves it to meet its patches.
  std::vector<Eigen::MatrixX3d> fitted;
  if (screen)
    for (const auto& s : superseded) fitted.push_back(s.first.surface.spline.control_points);
  auto* winner = best_capped(dense, target, options, screen ? Caps::screened : Caps::full,
                             judged, out, superseded, clock);
  if (winner && screen) {
    winner->first.surface.spline.control_points =
        fitted[static_cast<std::size_t>(winner - superseded.data())];
    deliver_round(dense, target, options, winner->second, clock, winner->first);
    if (!capped_better(winner->first, out)) winner = nullptr;
  }
  if (winner) adopt_round(std::move(*winner), out, best);
  superseded.clear();
}

int vertices_over(const std::vector<double>& distance, double limit) {
  int count = 0;
  for (double d : distance) count += d > limit;
  return count;
}

RefinementRound round_summary(const FittedSurface& out, const Round& round,
                              const FitSurfaceOptions& options) {
  RefinementRound r;
  r.domain_faces = out.surface.spline.space->domain_face_count();
  r.control_points = out.surface.spline.space->function_count();
  r.folds = out.surface_dihedral.over_90_deg;
  r.projection_rms = out.projection_rms;
  r.projection_max = out.projection_max;
  if (options.tolerance > 0.0)
    r.vertices_over_tolerance =
        vertices_over(round.vertex_distance, options.tolerance * out.bbox_diagonal);
  return r;
}

double input_diagonal(const ricci::Mesh& dense) {
  const Eigen::MatrixX3d x = ricci::vertex_positions(dense);
  return x.rows() > 0 ? (x.colwise().maxCoeff() - x.colwise().minCoeff()).norm() : 0.0;
}

// The domain split 1-to-4 (split_domain_faces) on the faces nearest to `points` and their
// neighbours.
ricci::Mesh refine_domain(const ricci::Mesh& domain, const ricci::Mesh& dense,
                          const std::vector<Eigen::Vector3d>& points) {
  Eigen::MatrixX3d queries(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i)
    queries.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  std::vector<char> near_vertex(domain.n_vertices(), 0);
  for (const auto& hit : ricci::closest_points(domain, queries))
    for (auto v : domain.fv_range(domain.face_handle(hit.face))) near_vertex[v.idx()] = 1;
  std::vector<char> refine(domain.n_faces(), 0);
  for (auto f : domain.faces())
    for (auto v : domain.fv_range(f)) refine[f.idx()] |= near_vertex[v.idx()];
  return split_domain_faces(domain, dense, refine);
}

// The midpoints of the tessellation's edges that fold.
std::vector<Eigen::Vector3d> fold_points(const FittedSurface& out) {
  std::vector<Eigen::Vector3d> points;
  const auto& x = out.tessellation.positions;
  for (const auto& e : out.surface_dihedral.fold_edges)
    points.emplace_back(0.5 * (x.row(e[0]) + x.row(e[1])).transpose());
  return points;
}

// The input's vertices farther than `limit` from the surface of `round`.
std::vector<Eigen::Vector3d> vertices_farther(const ricci::Mesh& dense, const Round& round,
                                              double limit) {
  std::vector<Eigen::Vector3d> points;
  for (std::size_t v = 0; v < round.vertex_distance.size(); ++v) {
    if (round.vertex_distance[v] > limit)
      points.push_back(ricci::to_eigen(dense.point(dense.vertex_handle(static_cast<int>(v)))));
  }
  return points;
}

// Where the domain is refined: the folds' midpoints and, with a tolerance, the input vertices
// farther than it from the surface.
std::vector<Eigen::Vector3d> refinement_points(const ricci::Mesh& dense,
                                               const FitSurfaceOptions& options,
                                               const FittedSurface& out, const Round& round) {
  std::vector<Eigen::Vector3d> points = fold_points(out);
  if (options.tolerance > 0.0) {
    const auto far = vertices_farther(dense, round, options.tolerance * out.bbox_diagonal);
    points.insert(points.end(), far.begin(), far.end());
  }
  return points;
}

// `faces` (flags by face of `domain`) grown by `rings` rings of edge neighbours.
std::vector<char> grown_by_rings(const ricci::Mesh& domain, const std::vector<char>& faces,
                                 int rings) {
  const std::vector<int> ring = rings_from_faces(domain, faces, rings);
  std::vector<char> grown(ring.size());
  for (std::size_t f = 0; f < ring.size(); ++f) grown[f] = ring[f] >= 0;
  return grown;
}

// Faces of the surface's domain (mesh indices) holding an edge of the tessellation that folds.
std::vector<char> faces_with_folds(const FittedSurface& out) {
  const ricci::Mesh& domain = out.surface.domain;
  const Tessellation& t = out.tessellation;
  const auto n = static_cast<long long>(t.positions.rows());
  std::unordered_set<long long> folds;
  for (const auto& e : out.surface_dihedral.fold_edges) folds.insert(e[0] * n + e[1]);
  std::vector<char> near(domain.n_faces(), 0);
  for (std::size_t k = 0; k < t.triangles.size(); ++k) {
    const int face = t.triangle_face[k];
    if (face < 0) continue;  // a patch
    for (int i = 0; i < 3; ++i) {
      const long long a = t.triangles[k][i], b = t.triangles[k][(i + 1) % 3];
      if (folds.count(std::min(a, b) * n + std::max(a, b))) near[face] = 1;
    }
  }
  return near;
}

// Domain faces of an open surface within `rings` rings of the input's boundary: the collar's
// ghost faces and those next to them (without a collar: the faces at the domain's boundary).
std::vector<char> faces_near_boundary(const FittedSurface& out, int rings) {
  const ricci::Mesh& domain = out.surface.domain;
  std::vector<char> near(domain.n_faces(), 0);
  const bool collar = out.collar_faces.size() == near.size();
  for (auto f : domain.faces()) {
    char& flag = near[static_cast<std::size_t>(f.idx())];
    if (collar) {
      flag = out.collar_faces[static_cast<std::size_t>(f.idx())] != 0;
    } else {
      for (auto v : domain.fv_range(f)) flag |= static_cast<char>(domain.is_boundary(v));
    }
  }
  return grown_by_rings(domain, near, rings);
}

// Whether no fold of `out` lies on a domain face within kBoundaryBandRings of an open input's
// boundary (faces_near_boundary); true on closed inputs.
bool folds_off_boundary_band(const FittedSurface& out) {
  if (out.input.boundary_loops == 0) return true;
  const std::vector<char> band = faces_near_boundary(out, kBoundaryBandRings);
  const std::vector<char> folded = faces_with_folds(out);
  for (std::size_t f = 0; f < folded.size() && f < band.size(); ++f)
    if (folded[f] && band[f]) return false;
  return true;
}

// A refined round is kept when it folds less, or as little with fewer vertices over the
// tolerance (with one), or as few with a lower RMS.
bool better(const FittedSurface& next, const Round& next_round, const FittedSurface& out,
            const Round& round, const FitSurfaceOptions& options) {
  const int folds_next = next.surface_dihedral.over_90_deg, folds = out.surface_dihedral.over_90_deg;
  if (folds_next != folds) return folds_next < folds;
  if (options.tolerance > 0.0) {
    const double limit = options.tolerance * next.bbox_diagonal;
    const int over_next = vertices_over(next_round.vertex_distance, limit);
    const int over = vertices_over(round.vertex_distance, limit);
    if (over_next != over) return over_next < over;
  }
  return next.projection_rms < out.projection_rms;
}

// Rings of edge neighbours around an open surface's collar that make up its boundary band for
// the fold rounds (open_fold_floor).
constexpr int kFoldFloorBandRings = 1;

// The fold rounds' floor for an open input: `face_smoothing` without the raise on the boundary
// band (the collar and the faces next to it, faces_near_boundary), except on the faces that
// folded in this series (`folded`, by face). The band's faces carry the boundary curve's samples,
// and a floor spread there from folds a ring or two inside pulls the surface's boundary off the
// scan's: mech-holes-shark.off's zigzag boundary, 0.441% of the diagonal from the scan's before
// its fold round, ended 0.504% away at a tooth tip the floor had reached.
std::vector<double> open_fold_floor(const FittedSurface& out,
                                    const std::vector<double>& face_smoothing,
                                    const std::vector<char>& folded) {
  const std::vector<char> band = faces_near_boundary(out, kFoldFloorBandRings);
  std::vector<double> floor = face_smoothing;
  for (std::size_t f = 0; f < floor.size() && f < band.size(); ++f)
    if (band[f] && !(f < folded.size() && folded[f])) floor[f] = 0.0;
  return floor;
}

// `floor` into `face_smoothing` (grown to its size): the larger of the two by face.
void raise_floor(const std::vector<double>& floor, std::vector<double>& face_smoothing) {
  face_smoothing.resize(floor.size(), 0.0);
  for (std::size_t f = 0; f < floor.size(); ++f)
    face_smoothing[f] = std::max(face_smoothing[f], floor[f]);
}

// Fold rounds: the faces around the folds left fit again with stronger fairing (the same
// space, so the domain's face indices stay), a round kept when it folds less; the replaced
// rounds go to `superseded`. Open inputs refit too while their folds lie off the boundary
// band, and fit the whole scan again otherwise (scan.domain and scan.fit.face_smoothing are
// left as the last round set them).
void fold_round_series(const ricci::Mesh& dense, const FitSurfaceOptions& options,
                       int taper_rings, ScanFitOptions& scan, Round& best,
                       Superseded& superseded, FoldFree& fold_free, StageClock& clock,
                       FittedSurface& out) {
  std::vector<double> face_smoothing;
  std::vector<char> folded;  // faces that folded in this series (open inputs' band)
  double level = options.fold_smoothing;
  // A refit keeps the boundary samples' weights of the round it repeats: where an open
  // input's folds (and so its raised floor) touch the band along the boundary, a whole fit
  // of the scan raises the samples it misses again (fit_scan's boundary reweighting), which
  // the boundary needs (mech-holes-shark.off's refined round: 0.68% of the diagonal refitted,
  // 0.44% fitted whole). Both may trade folds for error up to the goal (lion.off: the first
  // fold round, 40 -> 7 folds at 1.3 times the RMS, was refused).
  const bool closed = out.input.boundary_loops == 0;
  const double goal = options.fold_rms_goal * out.bbox_diagonal;
  const double rms_limit = std::max(options.fold_rms_growth * out.projection_rms, goal);
  // A jagged input folds itself (femur.off: 497 edges over 90 degrees) and a spline that follows
  // it folds there too; while every fold left lies that near the input's own, rounding them is
  // worth more error (crease_fold_rms_growth).
  const double crease_limit = std::max(options.crease_fold_rms_growth * out.projection_rms, goal);
  const std::vector<Eigen::Vector3d> input_folds =
      options.crease_fold_rms_growth > options.fold_rms_growth ? mesh_fold_points(dense)
                                                               : std::vector<Eigen::Vector3d>{};
  const double near_input_fold =
      kFoldNearInputFoldEdges * ricci::median_edge_length(out.surface.domain);
  int without_gain = 0;
  // Open inputs: the band along the boundary is smoothed where it folded (lion.off's last folds
  // are there, with the boundary curve pulled), nowhere else (open_fold_floor);
  // refit_folded_boundary leaves it out.
  for (int round = 1; round <= options.fold_rounds && out.surface_dihedral.over_90_deg > 0;
       ++round, level *= kFoldSmoothingStep) {
    clock.begin("refine");
    const bool at_input_folds =
        !input_folds.empty() && all_within(fold_points(out), input_folds, near_input_fold);
    FoldSmoothingOptions floor_options;
    floor_options.level = level;
    floor_options.taper_rings = taper_rings;
    merge_flags(faces_with_folds(out), folded);
    raise_floor(fold_smoothing_floor(out.surface.domain, faces_with_folds(out), floor_options),
                face_smoothing);
    std::pair<FittedSurface, Round> next;
    if (closed) {
      next = refit_round(dense, options, face_smoothing, best, clock, out);
    } else {
      scan.domain = best.domain;
      scan.boundary_follow.max_rounds = 0;
      scan.fit.face_smoothing = open_fold_floor(out, face_smoothing, folded);
      next = folds_off_boundary_band(out)
                 ? refit_round(dense, options, scan.fit.face_smoothing, best, clock, out)
                 : next_round(dense, scan, options, clock, out);
    }
    out.refinement.push_back(round_summary(next.first, next.second, options));
    // More smoothing would only raise the RMS. A refused round without folds may still be
    // delivered (fold_free_rms).
    if (next.first.projection_rms > (at_input_folds ? crease_limit : rms_limit)) {
      keep_if_fold_free(std::move(next), options, fold_free);
      break;
    }
    // Kept when better (by a hair), but the series ends there.
    const bool stalled =
        next.first.surface_dihedral.over_90_deg == out.surface_dihedral.over_90_deg &&
        std::abs(next.first.projection_rms - out.projection_rms) <
            kFoldRoundStall * out.projection_rms;
    if (!better(next.first, next.second, out, best, options)) {
      if (stalled || ++without_gain >= kFoldRoundsWithoutGain) break;
      // The folds it made elsewhere are smoothed too in the next round.
      merge_flags(faces_with_folds(next.first), folded);
      raise_floor(fold_smoothing_floor(out.surface.domain, faces_with_folds(next.first),
                                       floor_options),
                  face_smoothing);
      continue;
    }
    without_gain = 0;
    adopt_round(std::move(next), out, best, &superseded);
    if (stalled) break;
  }
}

// The fold rounds (fold_round_series) with the raised smoothing stepping down at its border;
// when they leave folds, closed inputs run them again from the same start with the smoothing
// tapered (kFoldTaperRings) and keep the series that does better. Neither wins everywhere:
// femur.off (a jagged scan) 19 folds stepped, 0 tapered; camel.off 0 stepped, 2 tapered.
void run_fold_rounds(const ricci::Mesh& dense, const FitSurfaceOptions& options,
                     ScanFitOptions& scan, Round& best, Superseded& superseded,
                     FoldFree& fold_free, StageClock& clock, FittedSurface& out) {
  if (out.surface_dihedral.over_90_deg == 0) return;
  const bool closed = out.input.boundary_loops == 0;
  std::optional<Attempt> start;
  if (closed) start = Attempt{out, best, {}};
  fold_round_series(dense, options, 0, scan, best, superseded, fold_free, clock, out);
  if (!start || out.surface_dihedral.over_90_deg == 0) return;
  Attempt stepped{std::move(out), std::move(best), {}};
  take_history(start->out, stepped.out);
  out = std::move(start->out);
  best = std::move(start->round);
  fold_round_series(dense, options, kFoldTaperRings, scan, best, start->superseded, fold_free,
                    clock, out);
  if (better(out, best, stepped.out, stepped.round, options)) {
    for (auto& s : start->superseded) superseded.push_back(std::move(s));
    return;
  }
  take_history(stepped.out, out);
  out = std::move(stepped.out);
  best = std::move(stepped.round);
}

// An open surface that folds is fitted once more on the same domain without the boundary curve
// (ScanFitOptions::boundary_curve): on a scan whose boundary zigzags where the domain's boundary
// could not follow it, pulling the spline onto it folds the band next to the boundary
// (mech-holes-shark.off: 0 folds without, 108 with). The round that folds less is kept. The
// fold rounds' raised smoothing is kept away from the band (faces flagged in `band`), where it
// moved the unpulled boundary (mech-holes-shark.off: 1.58% of the diagonal with it, 1.43%
// without).
void refit_folded_boundary(const ricci::Mesh& dense, const FitSurfaceOptions& options,
                           const std::vector<char>& band, ScanFitOptions scan, Round& best,
                           StageClock& clock, FittedSurface& out) {
  if (out.input.boundary_loops == 0 || out.surface_dihedral.over_90_deg == 0 ||
      scan.boundary_curve.weight == 0 || !out.collar_refused.empty())
    return;
  clock.begin("boundary refit");
  scan.domain = best.domain;
  scan.boundary_follow.max_rounds = 0;  // the domain keeps its followed boundary
  scan.boundary_curve.weight = 0;
  auto& smoothing = scan.fit.face_smoothing;
  for (std::size_t f = 0; f < smoothing.size() && f < band.size(); ++f)
    if (band[f]) smoothing[f] = 0.0;
  auto next = next_round(dense, scan, options, clock, out);
  if (next.first.surface_dihedral.over_90_deg >= out.surface_dihedral.over_90_deg) return;
  next.first.boundary_curve_dropped = true;
  adopt_round(std::move(next), out, best);
}

// The RMS goal (FitSurfaceOptions::rms_goal): the first round is refined around the input
// vertices farther than this many times the goal from its surface.
constexpr double kGoalRefineDistance = 2.5;
// The first round's projection is measured only when the fit's own RMS at its parameters
// (which the projection can only lower, up to the points fitted that are not input vertices)
// exceeds this share of the goal: a round well within it costs nothing more.
constexpr double kGoalCheckShare = 0.8;

// The next round on `best`'s domain refined around `where` (the followed boundary and the cone
// kept), its summary added to out.refinement. A round whose atlas or fit fails (turbine.off,
// genus 11: an intrinsic edge of length 0 on a refined domain) is recorded with its error and
// none returned: the rounds so far stand.
std::optional<std::pair<FittedSurface, Round>> refined_round(
    const ricci::Mesh& dense, ScanFitOptions& scan, const FitSurfaceOptions& options,
    StageClock& clock, const Round& best, const std::vector<Eigen::Vector3d>& where,
    FittedSurface& out) {
  clock.begin("refine");
  std::optional<ricci::Mesh> previous = scan.domain;
  scan.domain = refine_domain(best.domain, dense, where);
  scan.boundary_follow.max_rounds = 0;  // the refined domain keeps the followed boundary
  if (needs_singularity(out.input)) scan.atlas.singular_vertex = out.atlas.chosen_vertex;
  try {
    auto next = next_round(dense, scan, options, clock, out);
    out.refinement.push_back(round_summary(next.first, next.second, options));
    return next;
  } catch (const ricci::Error& e) {
    scan.domain = std::move(previous);
    RefinementRound failed;
    failed.error = e.what();
    out.refinement.push_back(std::move(failed));
    return std::nullopt;
  }
}

// One refinement toward the RMS goal: `best`'s domain split (refine_domain) around the input
// vertices farther than kGoalRefineDistance times the goal from its surface and the whole fit
// run again on it with the same cone; that round replaces `best`, which goes to `superseded`,
// and scan keeps the refined domain. Returns whether a round was adopted.
bool refine_toward_goal(const ricci::Mesh& dense, const FitSurfaceOptions& options,
                        ScanFitOptions& scan, Round& best, Superseded& superseded,
                        StageClock& clock, FittedSurface& out) {
  const double goal = options.rms_goal * out.bbox_diagonal;
  const std::vector<Eigen::Vector3d> where =
      vertices_farther(dense, best, kGoalRefineDistance * goal);
  if (where.empty()) return false;
  auto next = refined_round(dense, scan, options, clock, best, where, out);
  if (!next) return false;
  adopt_round(std::move(*next), out, best, &superseded);
  return true;
}

// The RMS goal on the first round (`best`, `out`): when its RMS (projection) exceeds
// options.rms_goal, one refinement toward it (refine_toward_goal).
// Returns whether the first round was measured (projected, its summary and, when refined, the
// new round's in out.refinement).
bool refine_to_rms_goal(const ricci::Mesh& dense, const FitSurfaceOptions& options,
                        ScanFitOptions& scan, Round& best, Superseded& superseded,
                        StageClock& clock, FittedSurface& out) {
  const double goal = options.rms_goal * out.bbox_diagonal;
  if (!(goal > 0.0) || options.refinement_rounds == 0 ||
      !(best.fit_rms_at_parameters > kGoalCheckShare * goal))
    return false;
  project_round(dense, clock, best, out);
  out.refinement.push_back(round_summary(out, best, options));
  if (out.projection_rms > goal) {
    if (best.early_caps) best.early_caps->wait();  // before the refinement's solves
    refine_toward_goal(dense, options, scan, best, superseded, clock, out);
  }
  return true;
}

// The rounds after the first (and its RMS goal) and the delivery, on `best` and `out`.
void refine_and_deliver(const ricci::Mesh& dense, const DeliveredTarget& target,
                        const FitSurfaceOptions& options, ScanFitOptions& scan, Round& best,
                        Superseded& superseded, StageClock& clock, FittedSurface& out) {
  // Refinement: the domain split where the surface folds or misses the input by more than the
  // tolerance, the same cone kept, and the whole fit run again; the best round is delivered.
  // Inputs that fold, without a tolerance: the fold rounds run first, on the first round. A
  // fold round refits on the same space at a fraction of a refinement round's cost, and the
  // refinement's small new faces can fold more than the first round did (horse.off: 9 -> 56;
  // the open bunny refined twice, 1.1M faces: 8 -> 10; both refined rounds thrown away). When
  // they leave no fold and the capped surface does not fold, it is delivered and the
  // refinement skipped; otherwise the first round goes on as without them (refinement, fold
  // rounds; `scan` as the first round left it), and an early attempt left with folds is
  // delivered instead if it is better. Open inputs take this route only when no fold lies in
  // the band along the boundary (folds_off_boundary_band): the refinement splits the band's
  // faces where it folds, which brings the surface's boundary to the scan's
  // (mech-holes-shark.off: 0.441% of the diagonal refined, 0.920% by the fold rounds alone).
  std::optional<Attempt> early;
  FoldFree fold_free;
  bool delivered = false, refined = false;
  if (options.tolerance == 0.0 && options.refinement_rounds > 0 && options.fold_rounds > 0 &&
      out.surface_dihedral.over_90_deg > 0 && folds_off_boundary_band(out)) {
    Attempt first{out, best, {}};
    const ScanFitOptions first_scan = scan;
    run_fold_rounds(dense, options, scan, best, superseded, fold_free, clock, out);
    const bool unfolded = out.surface_dihedral.over_90_deg == 0;
    if (unfolded) {
      // Capped, the surface must still not fold (else the refinement is tried).
      deliver_best_round(dense, target, options, superseded, best, clock, out);
      delivered = out.surface_dihedral.over_90_deg == 0;
    }
    if (!delivered) {
      if (!unfolded) early = Attempt{std::move(out), std::move(best), std::move(superseded)};
      FittedSurface& history = unfolded ? out : early->out;
      take_history(first.out, history);
      superseded.clear();
      out = std::move(first.out);
      best = std::move(first.round);
      scan = first_scan;
    }
  }
  for (int round = 1; round <= options.refinement_rounds; ++round) {
    const std::vector<Eigen::Vector3d> where = refinement_points(dense, options, out, best);
    if (where.empty()) break;
    auto next = refined_round(dense, scan, options, clock, best, where, out);
    if (!next || !better(next->first, next->second, out, best, options)) break;
    adopt_round(std::move(*next), out, best, &superseded);
    refined = true;
  }

  // Without a refined round they would repeat the early attempt's rounds exactly.
  if (!early || refined)
    run_fold_rounds(dense, options, scan, best, superseded, fold_free, clock, out);
  if (early && better(early->out, early->round, out, best, options)) {
    // The fold rounds on the first round did better than the refinement and its fold rounds.
    take_history(early->out, out);
    out = std::move(early->out);
    best = std::move(early->round);
    superseded = std::move(early->superseded);
  }

  if (!delivered) {
    const std::vector<char> band = out.input.boundary_loops > 0
                                       ? faces_near_boundary(out, kBoundaryBandRings)
                                       : std::vector<char>{};
    refit_folded_boundary(dense, options, band, scan, best, clock, out);
    deliver_best_round(dense, target, options, superseded, best, clock, out);
    deliver_fold_free(dense, target, options, fold_free, best, clock, out);
  }
}

// The fit's state after a refinement toward the RMS goal that left the RMS over it: the scan's
// options (its refined domain) and the round.
struct GoalRetry {
  ScanFitOptions scan;
  Attempt start;
};

// The surface delivered from a round still over the RMS goal folds: that round is refined once
// more toward the goal (refine_toward_goal) and the rounds after it run again
// (refine_and_deliver); the new surface is delivered when it is capped_better. The folds of
// such a fit sit where it misses the input, and the fold rounds may not trade more error for
// them (fold_rms_growth): generated genus 8 at 2400 faces on one layout kept 40 folds at 0.51%
// RMS after the first refinement, 0 folds at 0.17% after the second.
void retry_toward_goal(const ricci::Mesh& dense, const DeliveredTarget& target,
                       const FitSurfaceOptions& options, GoalRetry& retry, StageClock& clock,
                       Round& best, FittedSurface& out) {
  Attempt& start = retry.start;
  take_history(start.out, out);
  if (refine_toward_goal(dense, options, retry.scan, start.round, start.superseded, clock,
                         start.out)) {
    refine_and_deliver(dense, target, options, retry.scan, start.round, start.superseded,
                       clock, start.out);
    if (capped_better(start.out, out)) {
      out = std::move(start.out);
      best = std::move(start.round);
      return;
    }
  }
  take_history(out, start.out);
}

}  // namespace

std::string topology_mismatch(const FittedSurface& fitted) {
  const int loops = expected_boundary_loops(fitted);
  const int genus = fitted.input.genus;
  const int chi = 2 - 2 * genus - loops;
  for (const WatertightReport* t : {&fitted.topology, &fitted.float_topology}) {
    const char* what = t == &fitted.topology ? "" : " (welded as float)";
    if (!t->manifold()) return std::string("the surface") + what + " is not a manifold";
    if (t->boundary_loops != loops) {
      return std::string("the surface") + what + " has " + std::to_string(t->boundary_loops) +
             " boundary loops, " + std::to_string(loops) + " expected";
    }
    if (t->euler_characteristic != chi) {
      const int parity = 2 - loops - t->euler_characteristic;
      const std::string its_genus =
          parity >= 0 && parity % 2 == 0 ? " (genus " + std::to_string(parity / 2) + ")" : "";
      return std::string("the surface") + what + " has Euler characteristic " +
             std::to_string(t->euler_characteristic) + its_genus + ", the input " +
             std::to_string(chi) + " (genus " + std::to_string(genus) +
             ")" + (t->euler_characteristic > chi ? ": a patch capped a handle" : "");
    }
  }
  return "";
}

int minimum_domain_faces(int genus) { return 100 * std::max(1, genus + 1); }

void check_options(const FitSurfaceOptions& o,
                   const std::function<std::string(const std::string& field)>& name) {
  auto require = [&](bool ok, const std::string& field, const std::string& range) {
    if (!ok) throw ricci::InvalidInputError((name ? name(field) : field) + " must be " + range);
  };
  require(o.domain_faces >= 1, "domain_faces", "positive");
  require(o.degree >= 1 && o.degree <= kMaxDmsDegree, "degree",
          "in [1, " + std::to_string(kMaxDmsDegree) + "]");
  require(o.fairness_order() >= -1 && o.fairness_order() <= o.degree - 1, "fairness",
          "-1 (none) or in [0, degree - 1]");
  require(o.smoothing >= 0.0 && o.smoothing < 1e6, "smoothing", "in [0, 1e6)");
  require(o.density >= 0 && o.density <= 64, "density", "in [1, 64] (0: chosen by size)");
  require(o.density_refine_levels >= 0 && o.density_refine_levels <= 6, "density_refine_levels",
          "in [0, 6]");
  require(o.density_refine_turn_deg > 0.0 && o.density_refine_turn_deg < 180.0,
          "density_refine_turn_deg", "in (0, 180) degrees");
  require(o.cone_refinement.levels >= 0 && o.cone_refinement.levels <= 4, "cone_refinement",
          "in [0, 4]");
  require(o.cone_refinement.radial_levels >= 0 && o.cone_refinement.radial_levels <= 4,
          "cone_grading", "in [0, 4]");
  require(o.refinement_rounds >= 0 && o.refinement_rounds <= 8, "refinement_rounds",
          "in [0, 8]");
  require(o.tolerance >= 0.0 && o.tolerance < 1.0, "tolerance",
          "in [0, 1) (a fraction of the diagonal; 0: folds only)");
  require(o.max_surface_deviation >= 0.0 && o.max_surface_deviation <= 10.0,
          "max_surface_deviation", "in [0, 10] (a fraction of the diagonal; 0: off)");
  require(o.fold_rounds >= 0 && o.fold_rounds <= 8, "fold_rounds", "in [0, 8]");
  require(o.fold_smoothing > 0.0 && o.fold_smoothing < 1e6, "fold_smoothing", "in (0, 1e6)");
  require(o.fold_rms_growth >= 1.0, "fold_rms_growth", ">= 1");
  require(o.crease_fold_rms_growth >= 1.0, "crease_fold_rms_growth", ">= 1");
  require(o.small_hole_diameter >= 0.0 && o.small_hole_diameter < 1.0, "small_hole_diameter",
          "in [0, 1) (a fraction of the diagonal; 0: no hole capped)");
  require(o.fold_rms_goal >= 0.0 && o.fold_rms_goal < 1.0, "fold_rms_goal",
          "in [0, 1) (a fraction of the diagonal)");
  require(o.fold_free_rms >= 0.0 && o.fold_free_rms < 1.0, "fold_free_rms",
          "in [0, 1) (a fraction of the diagonal; 0: off)");
  require(o.rms_goal >= 0.0 && o.rms_goal < 1.0, "rms_goal",
          "in [0, 1) (a fraction of the diagonal; 0: none)");
}

FittedSurface fit_surface(const ricci::Mesh& input, const FitSurfaceOptions& options) {
  check_options(options);
  FittedSurface out;
  StageClock clock(out, options);
  // The fit sees the input with its small holes capped (same vertex indices); the delivered
  // surface is measured against the input as given.
  ricci::SmallHoleCaps holes = ricci::cap_small_holes(input, {options.small_hole_diameter});
  const ricci::Mesh& dense = holes.capped_loops > 0 ? holes.mesh : input;
  out.input = ricci::surface_topology(dense);
  out.bbox_diagonal = input_diagonal(dense);
  check_domain_size(dense, out.input, options);

  ScanFitOptions scan = scan_options(options);
  if (options.adaptive_domain && out.input.boundary_loops == 0) {
    clock.begin("domain");
    AdaptiveDomainOptions sizing = options.sizing;
    sizing.target_faces = options.domain_faces;
    AdaptiveDomain domain = adaptive_domain(dense, sizing);
    out.domain_base_faces = domain.base_faces;
    out.domain_split_faces = std::move(domain.split_faces);
    scan.domain = std::move(domain.mesh);
    if (needs_singularity(out.input) && options.singular_vertex < 0)
      scan.atlas.singular_vertex = split_cone_star(dense, scan);
  }
  if (options.singular_vertex >= 0) {
    clock.begin("singularity");
    // Checks the vertex's range and that it is interior.
    const int vertex = domain_singular_vertex(dense, options, scan.domain);
    if (needs_singularity(out.input)) scan.atlas.singular_vertex = vertex;
  }
  scan.progress = [&clock](const std::string& stage) { clock.begin(stage); };
  // The input's search tree beside the first round's (serial) simplification.
  std::shared_future<std::shared_ptr<const PreparedScan>> prepared = prepared_input(input);
  EarlyCaps early_caps;  // joined (if still running) when fit_surface returns or throws
  Round best = fit_round(dense, scan, options, 0, false, clock, out, &early_caps);
  // A round that folds, or is refined by the tolerance, is fitted again before any capping. One
  // that folds is seldom delivered: its capping stops.
  if (out.surface_dihedral.over_90_deg > 0) {
    early_caps.cancel();
  } else if (options.tolerance > 0.0) {
    early_caps.wait();
  }
  Superseded superseded;
  const bool measured = refine_to_rms_goal(dense, options, scan, best, superseded, clock, out);
  // A first round without folds and without a tolerance is the only one (nothing to refine):
  // it is measured once, capped; any other round is measured before the caps, as its
  // successors are.
  const bool single_round =
      !measured && out.surface_dihedral.over_90_deg == 0 && options.tolerance == 0.0;
  if (!single_round && !measured) {
    project_round(dense, clock, best, out);
    out.refinement.push_back(round_summary(out, best, options));
  }

  // A refinement toward the goal (its first round superseded) that left the RMS over it.
  std::optional<GoalRetry> retry;
  if (measured && !superseded.empty() && out.projection_rms > options.rms_goal * out.bbox_diagonal)
    retry = GoalRetry{scan, Attempt{out, best, superseded}};
  const DeliveredTarget target{input, holes, prepared};
  refine_and_deliver(dense, target, options, scan, best, superseded, clock, out);
  if (retry && out.surface_dihedral.over_90_deg > 0)
    retry_toward_goal(dense, target, options, *retry, clock, best, out);
  if (single_round) out.refinement.push_back(round_summary(out, best, options));

  clock.begin("measure");
  out.capped_holes = holes.capped_loops;  // on the round delivered
  out.capped_hole_diameter = holes.largest_diameter;
  measure_delivered(target, options, best.delivered, out);
  clock.finish();
  return out;
}

SurfaceFoldPlaces surface_fold_places(const FittedSurface& fitted) {
  const Tessellation& t = fitted.tessellation;
  std::vector<char> on_patch(static_cast<std::size_t>(t.positions.rows()), 0);
  for (std::size_t i = 0; i < t.triangles.size(); ++i)
    if (t.triangle_face[i] < 0)
      for (int v : t.triangles[i]) on_patch[static_cast<std::size_t>(v)] = 1;
  const ricci::Mesh& domain = fitted.surface.domain;
  const int cone = fitted.surface.singular_vertex;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double hole_radius = 0.0;
  if (cone >= 0 && cone < static_cast<int>(domain.n_vertices())) {
    centre = ricci::to_eigen(domain.point(domain.vertex_handle(cone)));
    for (const HoleFill& fill : fitted.surface.fills) {
      if (fill.rim.kind != Rim::Kind::cone_hole) continue;
      for (int f : fill.rim.covered_faces)
        for (auto v : domain.fv_range(domain.face_handle(f)))
          hole_radius = std::max(hole_radius, (ricci::to_eigen(domain.point(v)) - centre).norm());
    }
  }
  SurfaceFoldPlaces out;
  out.near_cone_radius = kNearConeHoleRadii * hole_radius;
  out.places = fold_places(fitted.surface_dihedral.fold_edges, t.positions, on_patch, centre,
                           out.near_cone_radius);
  return out;
}

}  // namespace spline

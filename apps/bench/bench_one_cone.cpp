// msp-bench one-cone / one-cone-one: the whole one-cone pipeline (valence modification, Ricci
// flow, cut graph, layout, atlas) on the bench meshes of the model collection (MSP_SHARED_MODELS,
// folder bench/) and the genus 1-3 models, each mesh in a child process so that its peak memory
// is its own; the figures of issue 8 against CEPS and Campen et al. (the collection's
// bench/README.md).
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>
#include <ricci/flow/linear_solver.h>
#include <ricci/mesh/generate.h>
#include <ricci/mesh/io.h>
#include <ricci/metric/curvature.h>
#include <ricci/metric/mesh_tables.h>
#include <ricci/metric/subdivide.h>
#include <ricci/pipeline/one_cone_atlas.h>

#include "bench/benchmarks.h"
#include "bench/child_run.h"
#include "msp/cli.h"
#include "msp/flow_options.h"
#include "ricci/util/cross2d.h"
#include "ricci/util/memory.h"
#include "ricci/util/stopwatch.h"

namespace msp::bench {

namespace {

using Sparse = Eigen::SparseMatrix<double>;

}  // namespace

// Lower triangle of the cotangent Laplacian plus 1e-8 times its mean diagonal (SPD without
// pinning a vertex): the one linear system a single-solve method factorises.
Eigen::SparseMatrix<double> regularised_cotangent_laplacian(const ricci::Mesh& mesh) {
  const ricci::MeshTables t = ricci::build_mesh_tables(mesh);
  const Eigen::MatrixX3d angles =
      ricci::corner_angles(t, ricci::mesh_edge_lengths(mesh), ricci::Geometry::euclidean);
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(9 * static_cast<size_t>(t.num_faces()) + static_cast<size_t>(t.num_vertices()));
  double diagonal = 0;
  for (int f = 0; f < t.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int i = t.face_vertices(f, (k + 1) % 3), j = t.face_vertices(f, (k + 2) % 3);
      const double w = 0.5 / std::tan(angles(f, k));
      triplets.emplace_back(i, i, w);
      triplets.emplace_back(j, j, w);
      triplets.emplace_back(std::max(i, j), std::min(i, j), -w);
      diagonal += 2 * w;
    }
  }
  const double shift = 1e-8 * diagonal / t.num_vertices();
  for (int v = 0; v < t.num_vertices(); ++v) triplets.emplace_back(v, v, shift);
  Eigen::SparseMatrix<double> L(t.num_vertices(), t.num_vertices());
  L.setFromTriplets(triplets.begin(), triplets.end());
  L.makeCompressed();
  return L;
}

// Best of 3: CHOLMOD supernodal analyse + factorise + solve; the CPU seconds of that best run
// in `cpu_seconds` when given.
double one_cholesky_seconds(const Eigen::SparseMatrix<double>& L, double* cpu_seconds) {
  double best = 1e300, best_cpu = 0.0;
  const Eigen::VectorXd rhs = Eigen::VectorXd::Ones(L.rows());
  for (int r = 0; r < 3; ++r) {
    ricci::SymmetricFactorization solver(ricci::LinearSolver::cholmod_supernodal);
    const ricci::StageTimer t0;
    solver.analyze(L);
    if (!solver.factorize(L)) throw std::runtime_error("cotangent Laplacian factorisation failed");
    const Eigen::VectorXd x = solver.solve(rhs);
    if (t0.wall.seconds() < best) {
      best = t0.wall.seconds();
      best_cpu = t0.cpu.seconds();
    }
    if (!x.allFinite()) throw std::runtime_error("cotangent Laplacian solve is not finite");
  }
  if (cpu_seconds) *cpu_seconds = best_cpu;
  return best;
}

double cotangent_cholesky_seconds(const ricci::Mesh& mesh, double* cpu_seconds) {
  return one_cholesky_seconds(regularised_cotangent_laplacian(mesh), cpu_seconds);
}

namespace {

// Faces of the central chart with negative / zero signed area, from the layout's double-double
// edge vectors, and those whose plain double corner positions give area <= 0.
struct FaceSigns {
  int flipped = 0, zero = 0, degenerate_in_doubles = 0;
};

FaceSigns face_signs(const ricci::LayoutE2Result& layout, const ricci::Mesh& sliced) {
  FaceSigns s;
  for (auto f : sliced.faces()) {
    int c[3], k = 0;
    for (auto v : sliced.fv_range(f)) c[k++] = v.idx();
    const double area =
        ricci::cross2d(layout.edge_vector(c[0], c[1]), layout.edge_vector(c[0], c[2]));
    if (area < 0) ++s.flipped;
    if (area == 0) ++s.zero;
    const Eigen::Vector2d a = layout.positions.row(c[0]), b = layout.positions.row(c[1]),
                          d = layout.positions.row(c[2]);
    if (!(ricci::cross2d(b - a, d - a) > 0)) ++s.degenerate_in_doubles;
  }
  return s;
}

// Ring distance (in edges) of every vertex from `source`.
std::vector<int> ring_distance(const ricci::Mesh& mesh, int source) {
  std::vector<int> depth(mesh.n_vertices(), -1);
  std::vector<int> queue{source};
  depth[static_cast<size_t>(source)] = 0;
  for (size_t i = 0; i < queue.size(); ++i) {
    for (auto w : mesh.vv_range(mesh.vertex_handle(queue[i]))) {
      if (depth[static_cast<size_t>(w.idx())] < 0) {
        depth[static_cast<size_t>(w.idx())] = depth[static_cast<size_t>(queue[i])] + 1;
        queue.push_back(w.idx());
      }
    }
  }
  return depth;
}

// Where the flow's line searches broke triangles: the first broken face per Newton iteration,
// its ring distance from the cone and its smallest and largest 3D corner angles (slivers of
// the input have one near 0 and one near pi).
void print_broken_trials(const ricci::OneConeAtlasResult& r) {
  const ricci::Mesh& mesh = r.problem.mesh;
  const std::vector<int> depth = r.problem.cone >= 0 ? ring_distance(mesh, r.problem.cone) : std::vector<int>();
  for (const ricci::BrokenTrial& b : r.flow.broken_faces) {
    const auto f = mesh.face_handle(b.face);
    int ring = 1 << 30;
    std::vector<Eigen::Vector3d> p;
    for (auto v : mesh.fv_range(f)) {
      if (!depth.empty()) ring = std::min(ring, depth[static_cast<size_t>(v.idx())]);
      p.emplace_back(mesh.point(v)[0], mesh.point(v)[1], mesh.point(v)[2]);
    }
    double lo = M_PI, hi = 0;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d a = p[static_cast<size_t>((k + 1) % 3)] - p[static_cast<size_t>(k)],
                            c = p[static_cast<size_t>((k + 2) % 3)] - p[static_cast<size_t>(k)];
      const double angle = std::atan2(a.cross(c).norm(), a.dot(c));
      lo = std::min(lo, angle);
      hi = std::max(hi, angle);
    }
    std::cerr << "  newton " << b.iteration << ": " << b.trials << " trials broke triangles, first face "
              << b.face << " (ring " << (depth.empty() ? -1 : ring) << " from the cone, 3D angles " << lo
              << " .. " << hi << ")\n";
  }
}

// The worst edge of the layout (where the closure error sits), the worst curvature, the
// broken line-search trials, the metric's extreme corner angles and the failed metrics.
void print_diagnostics(const ricci::OneConeAtlasResult& r) {
  const ricci::Mesh& sm = r.atlas.sliced.mesh;
  double worst = 0;
  int wa = 0, wb = 0;
  double wl = 0;
  const Eigen::VectorXd sl = ricci::sliced_edge_lengths(r.atlas.sliced, r.flow.lengths);
  for (auto e : sm.edges()) {
    const auto h = sm.halfedge_handle(e, 0);
    const int a = sm.from_vertex_handle(h).idx(), b = sm.to_vertex_handle(h).idx();
    const double err = std::abs(r.atlas.layout.edge_vector(a, b).norm() - sl[e.idx()]) / sl[e.idx()];
    if (err > worst) { worst = err; wa = a; wb = b; wl = sl[e.idx()]; }
  }
  const int oa = r.atlas.sliced.to_original_vertex[wa], ob = r.atlas.sliced.to_original_vertex[wb];
  if (r.problem.cone >= 0) {
    const std::vector<int> rings = ring_distance(r.problem.mesh, r.problem.cone);
    std::cerr << "worst edge rings from the cone " << rings[static_cast<size_t>(oa)] << ", valences "
              << r.problem.mesh.valence(r.problem.mesh.vertex_handle(oa)) << " "
              << r.problem.mesh.valence(r.problem.mesh.vertex_handle(ob)) << "\n";
  }
  std::cerr << "worst edge " << oa << "-" << ob << " rel " << worst << " length/diam " << wl / r.atlas.domain_diameter
            << " K err " << r.flow.curvature[oa] - r.flow.target[oa] << " " << r.flow.curvature[ob] - r.flow.target[ob]
            << " pos " << r.atlas.layout.positions.row(wa) << " seed " << r.atlas.layout.seed_face << "\n";
  Eigen::VectorXd kerr = (r.flow.curvature - r.flow.target).cwiseAbs();
  Eigen::Index worst_v;
  kerr.maxCoeff(&worst_v);
  std::cerr << "worst K vertex " << worst_v << " err " << kerr[worst_v] << " cone " << r.problem.cone << "\n";
  print_broken_trials(r);
  const ricci::MeshTables tables = ricci::build_mesh_tables(r.problem.mesh);
  const Eigen::MatrixX3d angles =
      ricci::corner_angles(tables, r.flow.lengths, ricci::Geometry::euclidean);
  Eigen::Index worst_face = 0, worst_corner = 0;
  const double smallest = angles.minCoeff(&worst_face, &worst_corner);
  std::cerr << "metric's smallest corner angle " << smallest << " (face " << worst_face << "), largest "
            << angles.maxCoeff() << ", corners below 1e-4: " << (angles.array() < 1e-4).count() << "\n";
  for (const std::string& failure : r.flow.failed_attempts) std::cerr << "failed: " << failure << "\n";
}

// "FAR:NEAR:RINGS[,...]" with FAR inversive-distance|circle-packing, NEAR circle-packing|tangent.
std::vector<ricci::ConeRingMetric> parse_ring_metrics(const std::string& text) {
  std::vector<ricci::ConeRingMetric> rules;
  std::stringstream list(text);
  std::string item;
  while (std::getline(list, item, ',')) {
    std::stringstream fields(item);
    std::string far, near, rings;
    std::getline(fields, far, ':');
    std::getline(fields, near, ':');
    std::getline(fields, rings, ':');
    std::string needle;
    std::getline(fields, needle, ':');
    ricci::ConeRingMetric rule;
    if (!needle.empty()) {
      rule.needle_angle = parse_double(needle, "a ring rule's needle angle") * M_PI / 180.0;
    }
    std::string nonnegative;
    std::getline(fields, nonnegative, ':');
    rule.nonnegative_inversive_distance = nonnegative == "nonnegative";
    rule.far = parse_scheme(far);
    rule.near = near == "tangent" ? ricci::Scheme::combinatorial : parse_scheme(near);
    rule.rings = parse_int(rings, "a ring rule's ring count");
    rules.push_back(rule);
  }
  return rules;
}

// The mesh of a row: a file, or "generated:G:FACES", the surface `msp generate --genus G --faces
// FACES` makes (seed 1), subdivided `levels` times by midpoints.
ricci::Mesh case_mesh(const std::string& path, int levels) {
  ricci::Mesh mesh;
  if (path.rfind("generated:", 0) == 0) {
    ricci::GenerateOptions generate;
    std::stringstream fields(path.substr(10));
    std::string genus, faces;
    std::getline(fields, genus, ':');
    std::getline(fields, faces, ':');
    generate.genus = parse_int(genus, "a generated case's genus");
    generate.target_faces = parse_int(faces, "a generated case's face count");
    mesh = ricci::generate_surface(generate);
  } else {
    mesh = ricci::read_mesh(path);
  }
  for (int i = 0; i < levels; ++i) mesh = ricci::subdivide_midpoint(mesh);
  return mesh;
}

}  // namespace

int run_one_cone_case(int argc, char** argv) {
  Args args(argc, argv, {"verbose", "cold-start"});
  args.require_known({"levels", "cone", "metric", "radii", "verbose", "cold-start", "warm-fraction", "cone-margin", "ring-valence", "rings",
                      "polish-threshold", "flat-flips", "ring-metric", "continuation", "collapse", "flip-deviation", "protect-rings", "seed-face", "save-metric", "write-mesh"});
  args.require_positionals(1, "msp-bench one-cone-one MESH [--levels N] [--cone auto|V] [--metric M] [--radii R] "
                            "[--collapse FRACTION] [--flat-flips DEGREES] [--flip-deviation FRACTION] "
                            "[--protect-rings N] [--ring-metric FAR:NEAR:RINGS[:NEEDLE_DEG[:nonnegative]]] "
                            "[--continuation STAGES] [--seed-face F] [--cold-start] [--warm-fraction F] [--verbose] [--write-mesh OUT]");
  const std::string path = args.positionals()[0];
  ricci::Stopwatch t0;
  ricci::Mesh mesh = case_mesh(path, args.get_int("levels", 0));
  const double read = t0.seconds();
  if (auto out = args.get("write-mesh")) {  // the row's mesh as a file (msp atlas OUT), no run
    ricci::write_mesh(mesh, *out);
    std::cout << nlohmann::json{{"mesh", path}, {"faces", mesh.n_faces()}, {"written", *out}}.dump()
              << std::endl;
    return 0;
  }

  ricci::OneConeAtlasOptions options;
  const std::string cone = args.get_or("cone", "auto");
  options.singular_vertex = cone == "auto" ? -1 : args.get_int("cone", -1);
  const bool intrinsic = args.get_or("metric", "") == "intrinsic-delaunay";
  if (intrinsic) options.route = ricci::FlowRoute::intrinsic_delaunay;
  if (args.has("metric") && !intrinsic) options.flow.scheme = parse_scheme(*args.get("metric"));
  if (args.has("radii")) options.flow.radii = parse_radii(*args.get("radii"));
  options.keep_metric = (args.has("metric") && !intrinsic) || args.has("radii");
  options.polish_threshold = args.get_double("polish-threshold", options.polish_threshold);
  options.valence.cone_valence_margin = args.get_int("cone-margin", options.valence.cone_valence_margin);
  options.valence.ring_valence = args.get_int("ring-valence", options.valence.ring_valence);
  options.valence.rings = args.get_int("rings", options.valence.rings);
  if (args.has("flat-flips")) {  // degrees between the faces' normals
    options.flip_flat_edges = true;
    options.flat_flips.max_normal_angle = args.get_double("flat-flips", 0.0) * M_PI / 180.0;
  }
  if (args.has("flip-deviation")) {  // fraction of the median edge length
    options.flip_flat_edges = true;
    options.flat_flips.max_relative_deviation = args.get_double("flip-deviation", 0.0);
  }
  options.flat_flips.protected_rings = args.get_int("protect-rings", 0);
  options.atlas.layout.seed_face = args.get_int("seed-face", -1);
  if (args.has("collapse")) {  // edges below this fraction of the median length
    options.collapse_short_edges = true;
    options.short_edges.relative_length = args.get_double("collapse", 0.0);
  }
  options.continuation.stages = args.get_int("continuation", 1);
  options.warm_start = !args.has("cold-start");  // the intrinsic flow from u = 0
  options.warm_start_fraction = args.get_double("warm-fraction", options.warm_start_fraction);
  if (args.has("ring-metric")) options.cone_ring_metrics = parse_ring_metrics(*args.get("ring-metric"));
  // The pipeline's resident memory, sampled (its peak, and with --verbose each stage's).
  std::unique_ptr<RssSampler> sampler;
  const auto peak_note = [&sampler] {
    return ", peak since the last line " + std::to_string(static_cast<int>(sampler->window_peak_mb())) +
           " MB";
  };
  if (args.has("verbose")) {
    options.flow.progress = [peak_note](const ricci::FlowProgress& p) {
      std::cerr << "  newton " << p.iteration << ": error " << p.max_error << ", step " << p.step << ", "
                << p.seconds << " s, " << memory_note() << peak_note() << "\n";
    };
    options.progress = [peak_note, t = ricci::Stopwatch()](const std::string& stage) {
      std::cerr << std::fixed << t.seconds() << " s: " << stage << std::defaultfloat << ", "
                << memory_note() << peak_note() << "\n";
    };
  }

  nlohmann::json j;
  j["mesh"] = path;
  j["faces"] = mesh.n_faces();
  j["read_seconds"] = read;
  ricci::use_one_malloc_arena(mesh.n_vertices());  // as msp atlas, before any thread allocates
  // The reference solve first, so that the process's peak is the larger of the two; the mesh
  // is then handed over to the pipeline, as msp atlas does.
  const ReferenceSolve reference = reference_solve(mesh);
  try {
    sampler = std::make_unique<RssSampler>();
    const ricci::OneConeAtlasResult r = ricci::build_one_cone_atlas(std::move(mesh), options);
    if (args.has("verbose")) std::cerr << "pipeline done, " << memory_note() << peak_note() << "\n";
    j["pipeline_sampled_peak_mb"] = sampler->stop();
    const auto& t = r.timings;
    const FaceSigns signs = face_signs(r.atlas.layout, r.atlas.sliced.mesh);
    j["status"] = "ok";
    j["kind"] = ricci::to_string(r.problem.kind);
    j["cone"] = r.chosen_vertex;
    j["splits"] = r.problem.valence_splits;
    j["flat_flips"] = r.flat_flips.flips;
    j["collapses"] = r.short_edges.collapses;
    j["non_delaunay_left"] = r.flat_flips.non_delaunay_left;
    j["flips_seconds"] = t.flips;
    j["metric"] = r.intrinsic ? "intrinsic-delaunay" : ricci::to_string(r.flow.metric.scheme);
    j["failed_metrics"] = r.flow.failed_attempts.size();
    j["choice"] = t.choice;
    j["valence"] = t.valence;
    j["flow"] = t.flow;
    j["polish"] = t.polish;
    j["atlas"] = t.atlas;
    j["distortion"] = t.distortion;
    j["total"] = t.flips + t.valence + t.flow + t.polish + t.atlas;
    j["total_with_choice"] = t.total;  // everything build_one_cone_atlas did, msp atlas' seconds
    j["cpu_total_with_choice"] = t.cpu_total;
    j["cpu_stages"] = {{"choice", t.cpu_choice}, {"valence", t.cpu_valence}, {"flow", t.cpu_flow},
                       {"polish", t.cpu_polish}, {"atlas", t.cpu_atlas},
                       {"distortion", t.cpu_distortion}};
    j["solves_for_choice"] = r.solves_for_choice;
    j["flows_for_choice"] = r.flows_for_choice;
    j["metric_route"] = r.flow.metric_name;
    j["intrinsic_flips"] = r.intrinsic_flips;
    j["newton"] = r.flow.iterations;
    j["warm_start"] = ricci::to_string(r.warm_start);
    j["line_search_trials"] = r.intrinsic_trials;
    j["factorizations"] = r.flow.factorizations;
    const auto& ft = r.flow.timings;
    j["flow_stages"] = {{"setup", ft.setup},         {"evaluation", ft.evaluation},
                        {"assembly", ft.assembly},   {"analysis", ft.analysis},
                        {"factorization", ft.factorization}, {"solve", ft.solve},
                        {"last_attempt_total", ft.total}};
    j["curvature_error"] = r.flow.max_error;
    j["polish_before"] = r.polish.error_before;
    j["polish_after"] = r.polish.error_after;
    j["polish_iterations"] = r.polish.iterations;
    j["polished"] = r.polished;
    j["flipped"] = signs.flipped;
    j["zero_area"] = signs.zero;
    j["degenerate_in_doubles"] = signs.degenerate_in_doubles;
    j["edge_error"] = r.atlas.layout.max_relative_length_error;
    j["transition"] = r.relative_transition_residual();
    if (args.has("verbose")) print_diagnostics(r);
    if (args.has("save-metric")) {
      const bool low = r.polished && r.polish.lengths == r.flow.lengths;
      save_flat_metric(*args.get("save-metric"), r.problem.mesh, r.flow.lengths,
                       low ? r.polish.lengths_low : Eigen::VectorXd(), r.problem.targets.curvature,
                       r.atlas.cut.root.idx());
    }
    j["qc_mean"] = r.distortion.quasi_conformal_mean;
    j["qc_max"] = r.distortion.quasi_conformal_max;
    j["qc_p50"] = r.distortion.quasi_conformal_p50;
    j["qc_area_mean"] = r.distortion.quasi_conformal_area_mean;
    j["qc_faces"] = r.distortion.faces;
    j["qc_skipped"] = r.distortion.skipped_faces;
  } catch (const std::exception& e) {
    j["status"] = std::string("failed: ") + e.what();
  }
  print_row_after_reference(j, reference);
  return 0;
}

int run_one_cone_benchmark(int argc, char** argv) {
  Args args(argc, argv, {"million", "high-genus"});
  args.require_known({"million", "high-genus", "metric", "radii", "only"});
  struct Case {
    std::string path, cone;
    int levels;
  };
  const std::string m = shared_models();
  std::vector<Case> cases;
  if (args.has("high-genus")) {  // issue 20: as `msp atlas X --json` runs them (automatic cone)
    for (const char* name : {"closed_g4plus/anchor.off", "closed_g4plus/fertility.off",
                             "closed_g4plus/couplingdown.off", "closed_g4plus/casting.off",
                             "closed_g4plus/turbine.off", "bench/genus3_10k.obj", "bench/genus3_100k.obj"}) {
      cases.push_back({m + "/" + name, "auto", 0});
    }
    for (int faces : {10000, 100000}) {
      for (int genus : {4, 6, 8, 10}) {
        cases.push_back({"generated:" + std::to_string(genus) + ":" + std::to_string(faces), "auto", 0});
      }
    }
  } else {
    for (const char* name : {"torus_10k", "genus2_10k", "genus3_10k", "sphere_10k", "cap_10k", "torus_100k",
                             "genus2_100k", "genus3_100k", "sphere_100k", "cap_100k"}) {
      cases.push_back({m + "/bench/" + name + ".obj", "0", 0});  // vertex 0, as bench/README.md
    }
    for (const char* name : {"closed_g1/elk.off", "closed_g1/kitten_nf20k.off", "closed_g1/rocker-arm.off",
                             "closed_g2/eight.off", "closed_g2/cup.off", "closed_g2/femur.off",
                             "closed_g2/joint.off", "closed_g3/genus3.off", "closed_g3/block.off",
                             "closed_g3/helmet.off", "closed_g3/elephant_cgal.off"}) {
      cases.push_back({m + "/" + name, "auto", 0});
    }
  }
  if (args.has("million")) {  // midpoint subdivision twice: 1.6M faces
    cases.push_back({m + "/bench/torus_100k.obj", "0", 2});
    cases.push_back({m + "/bench/genus2_100k.obj", "0", 2});
  }
  const std::string only = args.get_or("only", "");
  std::string extra;
  if (args.has("metric")) extra += " --metric " + *args.get("metric");
  if (args.has("radii")) extra += " --radii " + *args.get("radii");
  const std::string self = self_executable();

  std::cout << "One-cone pipeline per mesh, each in its own process. Seconds: read (OBJ/OFF), "
               "choice (automatic\nsingularity, 'auto' rows only), valence, flow, atlas (cut graph "
               "+ layout + charts +\ntransitions), total = clean-up + valence + flow + polish + atlas (all: with the choice);\nchol = one CHOLMOD "
               "analyse+factorise+solve of\nthe cotangent Laplacian of the same mesh (best of 3), "
               "ratio = total / chol; it: Newton steps; ptol: Ptolemy flips of the intrinsic flow.\nflip/zero: faces of the layout with negative/zero signed area "
               "(double-double positions); dbl: faces with area\n<= 0 in the plain double chart "
               "coordinates; edge: max relative edge-length error of the\nlayout; trans: transition "
               "residual / domain diameter; QC: quasi-conformal distortion vs the\ninput mesh (mean, mean weighted by 3D area as Crane's tools report it,\nmedian, max over faces); MB: "
               "peak RSS of the process (the larger of the run's and\nthe reference solve's, which runs first).\n\n";
  std::cout << std::left << std::setw(22) << "mesh" << std::right << std::setw(8) << "faces" << std::setw(6)
            << "cone" << std::setw(5) << "spl" << std::setw(7) << "read" << std::setw(7) << "choice"
            << std::setw(7) << "val" << std::setw(7) << "flow" << std::setw(7) << "atlas" << std::setw(7)
            << "total" << std::setw(7) << "all" << std::setw(7) << "chol" << std::setw(8) << "ratio" << std::setw(4) << "it" << std::setw(9) << "ptol"
            << std::setw(9) << "K err" << std::setw(5) << "flip" << std::setw(5) << "zero" << std::setw(5)
            << "dbl" << std::setw(9) << "edge" << std::setw(9) << "trans" << std::setw(8) << "QC mean" << std::setw(8) << "QC area" << std::setw(7) << "QC p50"
            << std::setw(10) << "QC max" << std::setw(7) << "MB"
            << "  metric\n";
  for (const Case& c : cases) {
    if (!only.empty() && c.path.find(only) == std::string::npos) continue;
    const std::string command = "'" + self + "' one-cone-one '" + c.path + "' --cone " + c.cone +
                                " --levels " + std::to_string(c.levels) + extra;
    const ChildResult child = run_child(command);
    const std::string name = case_label(c.path, c.levels);
    if (!child.parsed) {
      std::cout << std::left << std::setw(22) << name << " child failed: " << child.output << "\n";
      continue;
    }
    const nlohmann::json& j = child.json;
    std::cout << std::left << std::setw(22) << name << std::right << std::setw(8) << j["faces"].get<int>();
    if (j["status"] != "ok") {
      std::cout << "  " << j["status"].get<std::string>().substr(0, 200) << std::endl;
      continue;
    }
    const double total = j["total"].get<double>(), chol = j["cholesky"].get<double>();
    std::cout << std::setw(6) << j["cone"].get<int>() << std::setw(5) << j["splits"].get<int>() << std::fixed
              << std::setprecision(2) << std::setw(7) << j["read_seconds"].get<double>() << std::setw(7)
              << j["choice"].get<double>() << std::setw(7) << j["valence"].get<double>() << std::setw(7)
              << j["flow"].get<double>() << std::setw(7) << j["atlas"].get<double>() << std::setw(7) << total
              << std::setw(7) << j["total_with_choice"].get<double>()
              << std::setw(7) << chol << std::setprecision(1) << std::setw(8) << total / chol << std::setw(4)
              << j["newton"].get<int>() << std::setw(9) << j["intrinsic_flips"].get<int>() << std::scientific << std::setprecision(1) << std::setw(9)
              << j["curvature_error"].get<double>() << std::setw(5) << j["flipped"].get<int>() << std::setw(5)
              << j["zero_area"].get<int>() << std::setw(5) << j["degenerate_in_doubles"].get<int>()
              << std::setw(9) << j["edge_error"].get<double>() << std::setw(9) << j["transition"].get<double>()
              << std::fixed << std::setprecision(3) << std::setw(8) << j["qc_mean"].get<double>() << std::setw(8)
              << j["qc_area_mean"].get<double>() << std::setw(7)
              << j["qc_p50"].get<double>()
              << std::setprecision(1) << std::setw(10) << j["qc_max"].get<double>() << std::setprecision(0)
              << std::setw(7) << j["peak_mb"].get<double>() << "  " << j["metric_route"].get<std::string>()
              << (j["failed_metrics"].get<int>() ? " (after " + std::to_string(j["failed_metrics"].get<int>()) + " failed)" : "")
              << (j["qc_skipped"].get<int>() ? "; QC leaves out " + std::to_string(j["qc_skipped"].get<int>()) +
                                                   " faces flat in 3D"
                                             : "")
              << std::endl;
  }
  return 0;
}

}  // namespace msp::bench

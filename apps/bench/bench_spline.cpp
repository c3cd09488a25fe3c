// msp-bench spline / spline-fit: manifold DMS spline construction, fitting and evaluation.
//  spline:     the paper's Table 1 sizes (600-4000 domain faces, degree 3 and 4) on shared models
//              of the same genus: construction and fit times next to the paper's T_spline.
//  spline-fit: the scan pipeline on genus 0-3 models: fit RMS / max distance over the bbox
//              diagonal (closest-point projection onto the spline) and seconds per stage.
// Wall and CPU seconds are both printed: the machine is shared, and wall time under load
// overstates our cost.
#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <ricci/mesh/io.h>
#include <ricci/mesh/simplify.h>
#include <ricci/pipeline/one_cone_atlas.h>
#include <spline/fair/fair.h>
#include <spline/fit/fit.h>
#include <spline/manifold/manifold_space.h>

#include "bench/benchmarks.h"
#include "msp/cli.h"
#include "ricci/util/stopwatch.h"

namespace msp::bench {
namespace {

struct Stopwatch {
  ricci::Stopwatch wall;
  double cpu = now_cpu();
  static double now_cpu() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
  }
  [[nodiscard]] double wall_seconds() const { return wall.seconds(); }
  [[nodiscard]] double cpu_seconds() const { return now_cpu() - cpu; }
};

std::string shared(const std::string& relative) {
  return shared_models() + "/" + relative;
}

Eigen::MatrixX3d vertex_matrix(const ricci::Mesh& mesh) {
  Eigen::MatrixX3d points(static_cast<Eigen::Index>(mesh.n_vertices()), 3);
  for (auto v : mesh.vertices()) points.row(v.idx()) = ricci::to_eigen(mesh.point(v)).transpose();
  return points;
}

double diagonal(const Eigen::MatrixX3d& points) {
  return (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
}

// One row of the paper's Table 1 and the shared model of the same genus standing in for it.
struct PaperRow {
  const char* object;
  int genus, faces, degree;
  double t_spline;  // seconds, Table 1
  const char* model;
};
const PaperRow kTable1[] = {
    {"Bunny", 0, 621, 3, 3, "closed_g0/bunny_igl.off"},
    {"Rabbit", 0, 1038, 3, 8, "closed_g0/spot.obj"},
    {"Horse", 0, 4002, 3, 18, "closed_g0/horse.off"},
    {"Camel", 0, 2958, 3, 12, "closed_g0/camel.off"},
    {"Rockerarm", 1, 614, 3, 5, "closed_g1/rocker-arm.off"},
    {"Hypersheet", 1, 300, 3, 2, "closed_g1/elk.off"},
    {"Eight", 2, 806, 3, 3, "closed_g2/eight.off"},
    {"Vase", 2, 1480, 3, 10, "closed_g2/femur.off"},
    {"Cup", 2, 1929, 4, 18, "closed_g2/cup.off"},
    {"3-hole torus", 3, 878, 3, 4, "closed_g3/genus3.off"},
};

// Mean microseconds per evaluation (position, derivatives, normal) at random domain points.
double evaluation_microseconds(const spline::ManifoldSpline& s, int samples) {
  std::mt19937 rng(1);
  const auto& faces = s.space->domain_faces();
  std::uniform_int_distribution<std::size_t> pick(0, faces.size() - 1);
  std::uniform_real_distribution<double> unit(0.01, 1.0);
  std::vector<spline::DomainPoint> points;
  for (int i = 0; i < samples; ++i) {
    Eigen::Vector3d b(unit(rng), unit(rng), unit(rng));
    points.push_back({faces[pick(rng)], b / b.sum()});
  }
  double sink = 0.0;
  const Stopwatch watch;
  for (const auto& p : points) sink += s.evaluate(p).position.x();
  const double seconds = watch.cpu_seconds();
  if (sink == 42.0) std::printf(" ");  // keeps the loop
  return 1e6 * seconds / samples;
}


// --breakdown: where the squared error of the spline comes from. Per input vertex: distance to
// the spline (projection), to the domain mesh (the simplification's own error) and at the
// parameter (no projection); grouped by rim ring and by domain-mesh distance.
void print_breakdown(const spline::ScanFitResult& result, const Eigen::MatrixX3d& vertices,
                     double diag) {
  const auto& space = *result.spline.space;
  const auto domain_distance = ricci::closest_points(result.atlas.problem.mesh, vertices);
  const std::vector<int> rings = spline::domain_rim_rings(space);
  struct Sample {
    double spline, at_parameter, domain;
    int ring;
    Eigen::Index vertex;
  };
  std::vector<Sample> samples;
  for (Eigen::Index k = 0; k < vertices.rows(); ++k) {
    const auto& p = result.vertex_parameters[k];
    if (p.face < 0) continue;
    const Eigen::Vector3d x = vertices.row(k).transpose();
    const auto projection = spline::project_to_spline(result.spline, p, x);
    samples.push_back({projection.distance, (result.spline.evaluate(p).position - x).norm(),
                       domain_distance[k].distance, rings[space.domain_index(p.face)], k});
  }
  const auto rms = [&](auto member, auto keep) {
    double sum = 0.0;
    int n = 0;
    for (const auto& s : samples)
      if (keep(s)) sum += member(s) * member(s), ++n;
    return n > 0 ? 100.0 * std::sqrt(sum / n) / diag : 0.0;
  };
  const auto all = [](const Sample&) { return true; };
  const auto spline_d = [](const Sample& s) { return s.spline; };
  double total = 0.0;
  for (const auto& s : samples) total += s.spline * s.spline;
  std::printf("  last fit: assemble %.2f s, solve %.2f s, %d multiplier iterations, %d rounds\n",
              result.fit.seconds_assemble, result.fit.seconds_solve,
              result.fit.constraint_iterations, result.corrections);
  std::printf("  breakdown (%% of diagonal): spline rms %.4f, at parameters %.4f, domain mesh %.4f\n",
              rms(spline_d, all), rms([](const Sample& s) { return s.at_parameter; }, all),
              rms([](const Sample& s) { return s.domain; }, all));
  const auto group = [&](const char* name, auto keep) {
    int n = 0;
    double sum = 0.0;
    for (const auto& s : samples)
      if (keep(s)) sum += s.spline * s.spline, ++n;
    std::printf("    %-28s points %6d (%5.1f%%)  spline rms %.4f  share of sum sq %5.1f%%  domain rms %.4f\n",
                name, n, 100.0 * n / samples.size(), rms(spline_d, keep), 100.0 * sum / total,
                rms([](const Sample& s) { return s.domain; }, keep));
  };
  group("rim ring 0-2", [](const Sample& s) { return s.ring >= 0 && s.ring <= 2; });
  group("rim ring 3-5", [](const Sample& s) { return s.ring >= 3 && s.ring <= 5; });
  group("rim ring 6+", [](const Sample& s) { return s.ring >= 6 || s.ring < 0; });
  std::vector<double> dom;
  for (const auto& s : samples) dom.push_back(s.domain);
  std::sort(dom.begin(), dom.end());
  const double p90 = dom[dom.size() * 9 / 10], p50 = dom[dom.size() / 2];
  group("domain dist <= median", [&](const Sample& s) { return s.domain <= p50; });
  group("domain dist median..p90", [&](const Sample& s) { return s.domain > p50 && s.domain <= p90; });
  group("domain dist > p90", [&](const Sample& s) { return s.domain > p90; });
  std::vector<double> sp;
  for (const auto& s : samples) sp.push_back(s.spline);
  std::sort(sp.begin(), sp.end());
  const double q99 = sp[sp.size() * 99 / 100], q90 = sp[sp.size() * 9 / 10];
  group("worst 1% spline", [&](const Sample& s) { return s.spline > q99; });
  group("worst 10% spline", [&](const Sample& s) { return s.spline > q90; });
  std::vector<Sample> worst = samples;
  std::sort(worst.begin(), worst.end(),
            [](const Sample& a, const Sample& b) { return a.spline > b.spline; });
  spline::ManifoldSpline unity{result.spline.space,
                               Eigen::MatrixX3d::Ones(space.function_count(), 3)};
  for (std::size_t i = 0; i < std::min<std::size_t>(5, worst.size()); ++i) {
    const Sample& s = worst[i];
    const auto& p = result.vertex_parameters[s.vertex];
    const auto jet = result.spline.evaluate(p);
    std::printf("    sum of basis %.4f |F_u| %.3g |F_v| %.3g |F_uu| %.3g\n", unity.evaluate(p).position.x(),
                jet.du.norm(), jet.dv.norm(), jet.duu.norm());
    std::printf("    worst vertex %6td: spline %.4f at parameter %.4f domain %.4f ring %d face %d "
                "bary (%.3f %.3f %.3f)\n",
                static_cast<std::ptrdiff_t>(s.vertex), 100 * s.spline / diag,
                100 * s.at_parameter / diag, 100 * s.domain / diag, s.ring, p.face,
                p.barycentric[0], p.barycentric[1], p.barycentric[2]);
  }
}

}  // namespace

int run_spline_benchmark(int argc, char** argv) {
  // Arguments, if any, pick rows by paper name or model path (e.g. "Horse", to profile one row).
  const std::vector<std::string> picked(argv, argv + argc);
  const auto wanted = [&](const PaperRow& row) {
    return picked.empty() || std::find(picked.begin(), picked.end(), row.object) != picked.end() ||
           std::find(picked.begin(), picked.end(), row.model) != picked.end();
  };
  std::printf(
      "Manifold DMS spline: paper Table 1 sizes on shared models of the same genus\n"
      "construction = home clouds + every chart's planar space + initial control points;\n"
      "fit = parameters (closest point of every input vertex) + normal equations + CHOLMOD, free;\n"
      "fair = eq. 14 projection of that fit, r = 1; fit_r1 = the fit inside eq. 14's constraints "
      "(r = 1) instead.\nCPU seconds of the process (both worker threads counted; the machine is "
      "shared, wall time under load overstates our cost).\nspeedup = T_spline / (construction + "
      "fit + fair); speedup_r1 = T_spline / (construction + fit_r1); eval_us = one position + "
      "derivatives + normal;\nwall_total = wall seconds of construction + fit + fair (2 worker "
      "threads in the fit; inflated when the machine is loaded, see uptime).\n\n");
  std::printf("%-13s %-28s %2s %5s %2s %6s %6s %7s %7s %7s %7s %7s %8s %8s %10s %8s %10s\n",
              "paper row", "model", "g", "Nf", "n", "Nc", "points", "constr", "fit", "fair",
              "fit_r1", "total", "T_spline", "speedup", "speedup_r1", "eval_us", "wall_total");
  for (const PaperRow& row : kTable1) {
    if (!wanted(row)) continue;
    const ricci::Mesh dense = ricci::read_mesh(shared(row.model));
    ricci::SimplifyOptions simplify;
    simplify.target_faces = row.faces;
    // A fixed-connectivity metric: the spline space is built on the simplified mesh itself.
    ricci::OneConeAtlasOptions fixed;
    fixed.intrinsic_first = false;
    const auto atlas =
        ricci::build_one_cone_atlas(ricci::simplify_mesh(dense, simplify).mesh, fixed);
    const ricci::Mesh& mesh = atlas.problem.mesh;

    Stopwatch watch;
    spline::ManifoldSplineOptions options;
    options.degree = row.degree;
    auto space = std::make_shared<spline::ManifoldSplineSpace>(mesh, atlas.atlas, options);
    for (std::size_t c = 0; c < atlas.atlas.charts.size(); ++c)
      (void)space->chart_space(static_cast<int>(c));
    const Eigen::MatrixX3d initial = spline::piecewise_linear_control_points(*space, mesh);
    const double construction = watch.cpu_seconds();
    const double construction_wall = watch.wall_seconds();

    watch = Stopwatch();
    const Eigen::MatrixX3d data = vertex_matrix(dense);
    const auto closest = ricci::closest_points(mesh, data);
    std::vector<spline::DomainPoint> parameters;
    for (const auto& c : closest) {
      parameters.push_back({space->in_domain(c.face) ? c.face : -1, c.barycentric});
    }
    const double parameter_seconds = watch.cpu_seconds();
    const double parameter_wall = watch.wall_seconds();
    watch = Stopwatch();
    const auto fit = spline::fit_control_points(*space, parameters, data, initial);
    const double fit_seconds = parameter_seconds + watch.cpu_seconds();
    const double fit_wall = parameter_wall + watch.wall_seconds();

    watch = Stopwatch();
    spline::FairOptions fair_options;
    fair_options.r = 1;
    const auto faired = spline::fair(*space, fit.control_points, fair_options);
    const double fair_seconds = watch.cpu_seconds();
    const double fair_wall = watch.wall_seconds();

    watch = Stopwatch();
    spline::FitOptions constrained;
    constrained.constraint_r = 1;
    (void)spline::fit_control_points(*space, parameters, data, initial, constrained);
    const double fit_r1_seconds = parameter_seconds + watch.cpu_seconds();

    const double total = construction + fit_seconds + fair_seconds;
    const double total_wall = construction_wall + fit_wall + fair_wall;
    const spline::ManifoldSpline surface{space, faired.control_points};
    std::printf(
        "%-13s %-28s %2d %5d %2d %6d %6d %7.3f %7.3f %7.3f %7.3f %7.3f %8.0f %7.0fx %9.0fx "
        "%8.1f %10.3f\n",
        row.object, row.model, row.genus, space->domain_face_count(), row.degree,
        space->function_count(), fit.points, construction, fit_seconds, fair_seconds,
        fit_r1_seconds, total, row.t_spline, row.t_spline / total,
        row.t_spline / (construction + fit_r1_seconds), evaluation_microseconds(surface, 20000),
        total_wall);
    std::fflush(stdout);
  }
  return 0;
}

int run_spline_fit_benchmark(int argc, char** argv) {
  std::vector<std::string> models;
  spline::ScanFitOptions options;
  std::vector<int> rs{1, 0, -1};
  bool breakdown = false;
  for (int i = 0; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--r" && i + 1 < argc)
      rs = {parse_int(argv[++i], "option " + arg)};
    else if (arg == "--faces" && i + 1 < argc)
      options.domain_faces = parse_int(argv[++i], "option " + arg);
    else if (arg == "--degree" && i + 1 < argc)
      options.degree = parse_int(argv[++i], "option " + arg);
    else if (arg == "--lambda" && i + 1 < argc)
      options.fit.smoothing = parse_double(argv[++i], "option " + arg);
    else if (arg == "--rim-lambda" && i + 1 < argc)
      options.fit.rim_smoothing = parse_double(argv[++i], "option " + arg);
    else if (arg == "--correct-steps" && i + 1 < argc)
      options.correction_iterations = parse_int(argv[++i], "option " + arg);
    else if (arg == "--correct" && i + 1 < argc)
      options.parameter_corrections = parse_int(argv[++i], "option " + arg);
    else if (arg == "--breakdown")
      breakdown = true;
    else if (arg == "--project")
      options.constrained_fit = false;
    else
      models.push_back(arg);
  }
  if (models.empty()) {
    for (const char* dir : {"closed_g0", "closed_g1", "closed_g2", "closed_g3"}) {
      std::vector<std::string> found;
      for (const auto& entry : std::filesystem::directory_iterator(shared(dir))) {
        if (entry.path().extension() != ".ply") found.push_back(entry.path().string());
      }
      std::sort(found.begin(), found.end());
      models.insert(models.end(), found.begin(), found.end());
    }
  }
  std::printf(
      "Scan fit (spline::fit_scan): simplify to ~%d faces, one-cone atlas, degree %d, fit "
      "(lambda %g) to vertices + face centroids, %s, %d parameter-correction round(s);\nerrors: distance of every input vertex "
      "covered by the spline (not over the cone's hole / the puncture; 'uncov': input vertices "
      "and face centroids left out of fit and errors)\nafter projection onto the spline (Gauss-Newton), RMS / max over the bbox "
      "diagonal, in %%. free = no constraint, no fairing.\nSeconds (wall) of the first r's "
      "stages; 'corr' = the correction rounds (projections + refits); 'errors' = projection of "
      "the vertices.\n"
      "options: --faces N --degree n --r R (only this r; -1 = free) --lambda L --project "
      "--correct K (parameter-correction rounds) --rim-lambda L --breakdown\n\n",
      options.domain_faces, options.degree, options.fit.smoothing,
      options.constrained_fit ? "subject to eq. 14's constraints of r (constrained fit)"
                              : "then fairing of r by eq. 14's projection",
      options.parameter_corrections);
  std::printf("%-36s %6s %6s %6s %6s", "model", "V", "dom_F", "Nc", "uncov");
  for (int r : rs) {
    const std::string name = r < 0 ? "free" : "r=" + std::to_string(r);
    std::printf(" %8s_rms %8s_max", name.c_str(), name.c_str());
  }
  std::printf(" %6s %6s %6s %6s %6s %6s %6s\n", "simpl", "atlas", "space", "param", "fit", "corr",
              "errors");
  for (const std::string& path : models) {
    const std::string name = std::filesystem::path(path).parent_path().filename().string() + "/" +
                             std::filesystem::path(path).filename().string();
    try {
      const ricci::Mesh dense = ricci::read_mesh(path);
      const Eigen::MatrixX3d vertices = vertex_matrix(dense);
      const double diag = diagonal(vertices);
      std::string cells;
      spline::ScanFitTimings first{};
      double first_errors = 0.0;
      int faces = 0, functions = 0, uncovered = 0;
      for (std::size_t i = 0; i < rs.size(); ++i) {
        options.fair_r = rs[i];
        const auto result = spline::fit_scan(dense, options);
        const Stopwatch watch;
        const auto errors = spline::fit_errors(result.spline, result.vertex_parameters, vertices);
        char cell[64];
        std::snprintf(cell, sizeof cell, " %11.4f %12.4f", 100 * errors.rms / diag,
                      100 * errors.max / diag);
        cells += cell;
        if (breakdown) print_breakdown(result, vertices, diag);
        if (i == 0) {
          first = result.timings;
          first_errors = watch.wall_seconds();
          faces = result.spline.space->domain_face_count();
          functions = result.spline.space->function_count();
          uncovered = result.uncovered_points;
        }
      }
      std::printf("%-36s %6zu %6d %6d %6d%s %6.2f %6.2f %6.2f %6.2f %6.2f %6.2f %6.2f\n",
                  name.c_str(), dense.n_vertices(), faces, functions, uncovered, cells.c_str(),
                  first.simplify, first.atlas, first.space, first.parameters, first.fit,
                  first.correction, first_errors);
    } catch (const std::exception& e) {
      std::printf("%-36s error: %s\n", name.c_str(), e.what());
    }
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace msp::bench

// msp-bench eval / msp-bench bezier: the evaluation API of spline/surface on a fitted model.
//  eval:   microseconds per point of evaluate_surface (position, derivatives, normal, curvatures),
//          one thread and the parallel batch; ClosestPointIndex build seconds and microseconds
//          per query (targets near the surface).
//  bezier: bezier_patches seconds, patches and knot segments per face.
// The surface is spline::fit_surface's (msp fit's) at --faces domain faces (default 1000) of
// --model (default models/genus2.off, run from the repository root).
#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "bench/benchmarks.h"
#include "msp/cli.h"
#include "ricci/mesh/io.h"
#include "spline/surface/fit_surface.h"
#include "spline/surface/bezier.h"
#include "spline/surface/closest_point.h"
#include "spline/surface/evaluate.h"

namespace msp::bench {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

struct SurfaceArgs {
  std::string model = "models/genus2.off";
  int faces = 1000;
  int points = 20000;
  int threads = 2;
};

SurfaceArgs parse(int argc, char** argv) {
  SurfaceArgs a;
  for (int i = 0; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--model" && i + 1 < argc) {
      a.model = argv[++i];
    } else if (arg == "--faces" && i + 1 < argc) {
      a.faces = parse_int(argv[++i], "option " + arg);
    } else if (arg == "--points" && i + 1 < argc) {
      a.points = parse_int(argv[++i], "option " + arg);
    } else if (arg == "--threads" && i + 1 < argc) {
      a.threads = parse_int(argv[++i], "option " + arg);
    }
  }
  return a;
}

spline::SplineSurface fitted_surface(const SurfaceArgs& a) {
  spline::FitSurfaceOptions options;
  options.domain_faces = a.faces;
  const auto start = Clock::now();
  spline::SplineSurface s = spline::fit_surface(ricci::read_mesh(a.model), options).surface;
  const spline::ManifoldSplineSpace& space = *s.spline.space;
  std::printf("%s: %d domain faces (%d in the spline), degree %d, %zu fills, fit %.2f s\n",
              a.model.c_str(), space.face_count(), space.domain_face_count(), space.degree(),
              s.fills.size(), seconds_since(start));
  return s;
}

std::vector<spline::DomainPoint> random_points(const spline::SplineSurface& s, int count) {
  std::vector<int> faces;
  for (int f : s.spline.space->domain_faces()) {
    if (s.skipped_faces.empty() || s.skipped_faces[f] == 0) faces.push_back(f);
  }
  std::mt19937 rng(1);
  std::uniform_int_distribution<std::size_t> pick(0, faces.size() - 1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<spline::DomainPoint> points;
  for (int i = 0; i < count; ++i) {
    Eigen::Vector3d b(u(rng), u(rng), u(rng));
    points.push_back({faces[pick(rng)], b / b.sum()});
  }
  return points;
}

}  // namespace

int run_eval_benchmark(int argc, char** argv) {
  const SurfaceArgs a = parse(argc, argv);
  const spline::SplineSurface s = fitted_surface(a);
  const std::vector<spline::DomainPoint> points = random_points(s, a.points);
  double sink = 0.0;
  auto t = Clock::now();
  for (const auto& p : points) sink += spline::evaluate_surface(s, p).curvature.mean;
  const double single = seconds_since(t);
  t = Clock::now();
  const auto batch = spline::evaluate_surface(s, points, a.threads);
  const double parallel = seconds_since(t);
  std::printf("evaluate_surface (position, du..dvv, normal, K, H, k1, k2): %.2f us/point on one "
              "thread, %.2f us/point batch on %d threads (%d points)\n",
              1e6 * single / a.points, 1e6 * parallel / a.points, a.threads, a.points);

  spline::ClosestPointOptions options;
  options.threads = a.threads;
  t = Clock::now();
  const spline::ClosestPointIndex index(s, options);
  const double build = seconds_since(t);
  const int queries = std::max(1, a.points / 10);
  Eigen::MatrixX3d targets(queries, 3);
  std::mt19937 rng(2);
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (int i = 0; i < queries; ++i) {
    const Eigen::Vector3d n = batch[static_cast<std::size_t>(i)].normal;
    // Off the surface along the normal and sideways, ~1% of a unit-size model.
    targets.row(i) = (batch[static_cast<std::size_t>(i)].position + 0.01 * n +
                      0.01 * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)))
                         .transpose();
  }
  t = Clock::now();
  double candidates = 0.0;
  for (int i = 0; i < queries; ++i) {
    candidates += index.find(Eigen::Vector3d(targets.row(i).transpose())).candidates;
  }
  const double one = seconds_since(t);
  t = Clock::now();
  const auto found = index.find_all(targets);
  const double many = seconds_since(t);
  std::printf("closest point: index %.3f s (%d triangles), %.1f us/query on one thread, %.1f "
              "us/query batch on %d threads, %.2f candidates per query (%d queries)\n",
              build, index.triangle_count(), 1e6 * one / queries, 1e6 * many / queries,
              a.threads, candidates / queries, queries);
  return sink == 12345.0 && found.empty() ? 1 : 0;
}

int run_bezier_benchmark(int argc, char** argv) {
  const SurfaceArgs a = parse(argc, argv);
  const spline::SplineSurface s = fitted_surface(a);
  spline::BezierOptions options;
  options.threads = a.threads;
  const auto t = Clock::now();
  const spline::BezierExport e = spline::bezier_patches(s, options);
  const double seconds = seconds_since(t);
  std::printf("bezier_patches: %.2f s on %d threads, %d faces, %zu patches (%.1f per face), "
              "%.1f knot segments per face, %zu control points\n",
              seconds, a.threads, e.faces, e.patches.size(),
              static_cast<double>(e.patches.size()) / std::max(1, e.faces),
              static_cast<double>(e.knot_segments) / std::max(1, e.faces),
              e.patches.size() * static_cast<std::size_t>((e.degree + 1) * (e.degree + 2) / 2));
  return 0;
}

}  // namespace msp::bench

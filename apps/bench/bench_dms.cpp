// msp-bench dms [grid_size]: cost of the DMS basis on a jittered grid triangulation of [0,1]^2.
// Per degree: DAG nodes and bytes per triangle, build time per triangle, time per point for all
// non-zero basis functions with gradients and Hessians (evaluate_basis), values only
// (BasisDerivatives::none, as the fit's data rows use), for a spline with 3D control points
// (evaluate), and the worst partition-of-unity error seen.
#include <ctime>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "bench/benchmarks.h"
#include "msp/cli.h"
#include "spline/basis/planar_space.h"
#include "spline/knots/knot_cloud.h"
#include "spline/planar/perturbed_grid.h"

namespace msp::bench {
namespace {

// Process CPU time: the machine is shared, and wall time would count other jobs.
struct Clock {
  using time_point = std::clock_t;
  static time_point now() { return std::clock(); }
};

double microseconds_since(Clock::time_point start) {
  return 1e6 * static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
}

}  // namespace

int run_dms_benchmark(int argc, char** argv) {
  const int m = argc > 0 ? parse_int(argv[0], "the grid size") : 16;
  const spline::PlanarTriangulation t = spline::perturbed_grid(m, 0.3, 7);
  std::printf("jittered grid %dx%d, %zu triangles; points uniform in [0.2,0.8]^2; CPU time\n", m, m,
              t.triangles.size());
  std::printf("%6s %10s %12s %14s %12s %12s %13s %14s %10s\n", "degree", "nodes/tri", "KB/tri",
              "build us/tri", "functions", "basis us/pt", "values us/pt", "spline us/pt",
              "max|PU-1|");
  for (int n = 2; n <= 5; ++n) {
    const std::vector<spline::KnotCloud> clouds = spline::make_knot_clouds(t, n);
    const auto build_start = Clock::now();
    const spline::PlanarDmsSpace space(t, clouds);
    const double build = microseconds_since(build_start) / space.triangle_count();
    double nodes = 0.0, bytes = 0.0;
    for (int i = 0; i < space.triangle_count(); ++i) {
      nodes += space.triangle_basis(i).node_count();
      bytes += static_cast<double>(space.triangle_basis(i).memory_bytes());
    }
    std::mt19937 rng(n);
    std::uniform_real_distribution<double> unit(0.2, 0.8);
    std::vector<Eigen::Vector2d> points(2000);
    for (Eigen::Vector2d& u : points) u = Eigen::Vector2d(unit(rng), unit(rng));
    double worst = 0.0, functions = 0.0;
    const auto basis_start = Clock::now();
    for (const Eigen::Vector2d& u : points) {
      const std::vector<spline::BasisSample> samples = space.evaluate_basis(u);
      double sum = 0.0;
      for (const spline::BasisSample& s : samples) sum += s.jet.value;
      worst = std::max(worst, std::abs(sum - 1.0));
      functions += static_cast<double>(samples.size());
    }
    const double per_point = microseconds_since(basis_start) / static_cast<double>(points.size());
    double value_sum = 0.0;
    const auto values_start = Clock::now();
    for (const Eigen::Vector2d& u : points) {
      for (const spline::BasisSample& s :
           space.evaluate_basis(u, {}, spline::BasisDerivatives::none)) {
        value_sum += s.jet.value;
      }
    }
    const double values_per_point =
        microseconds_since(values_start) / static_cast<double>(points.size());
    const Eigen::MatrixXd control = Eigen::MatrixXd::Random(space.function_count(), 3);
    double checksum = 0.0;
    const auto spline_start = Clock::now();
    for (const Eigen::Vector2d& u : points) checksum += space.evaluate(control, u).value.sum();
    const double spline_per_point =
        microseconds_since(spline_start) / static_cast<double>(points.size());
    std::printf("%6d %10.0f %12.1f %14.1f %12.1f %12.1f %13.1f %14.1f %10.2e%s\n", n,
                nodes / space.triangle_count(), bytes / space.triangle_count() / 1024.0, build,
                functions / static_cast<double>(points.size()), per_point, values_per_point,
                spline_per_point, worst,
                std::isfinite(checksum + value_sum) ? "" : " (non-finite!)");
  }
  return 0;
}

}  // namespace msp::bench

// msp-bench adaptive [--rms F] [--from N] [--base-share F] [--max-turn D] [--thickness E]
// [--by-turn] [--by-residual] [--relax N] [--closest] [--adaptive-only] [paths...]: the adaptive
// domain (msp fit --adaptive-domain) against the uniform one. For each model and each domain, fit_surface on a
// ladder of domain targets (400 up, x1.25) until the delivered surface's RMS over every
// input vertex falls below F (0.1% of the diagonal): per step the domain faces, control points,
// RMS and max over the diagonal, folds and seconds (and as a multiple of one CHOLMOD solve of
// the scan's cotangent Laplacian); then the control points each domain needs for F (log-linear
// between the two steps around it) and their ratio. Refinement and fold rounds are off: the
// domains alone are compared. --from starts both ladders at another target; --base-share,
// --max-turn, --thickness, --by-turn (split by normal turn, not by the scan's deviation),
// --by-residual (by what a local quadric misses of the scan), --relax and --closest (split
// vertices on the closest scan point only, SplitPlacement::closest_point) set the adaptive
// domain's sizing (AdaptiveDomainOptions); --adaptive-only skips the uniform ladder.
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "bench/benchmarks.h"
#include "msp/cli.h"
#include "ricci/mesh/io.h"
#include "ricci/util/stopwatch.h"
#include "spline/surface/fit_surface.h"

namespace msp::bench {
namespace {

constexpr int kFirstTarget = 400;
constexpr double kStep = 1.25;
constexpr int kLastTarget = 20000;

struct Ladder {
  int first_target = kFirstTarget;
  double goal = 1e-3;
  spline::AdaptiveDomainOptions sizing;
  bool uniform = true;  // run the uniform ladder too
};

struct Step {
  int control_points = 0;
  double rms = 0.0;  // over the diagonal
};

// Control points at `goal` RMS, log-linear between the last step above it and the first below;
// -1 when the ladder never reached it.
double control_points_at(const std::vector<Step>& steps, double goal) {
  for (std::size_t k = 0; k < steps.size(); ++k) {
    if (steps[k].rms > goal) continue;
    if (k == 0) return steps[k].control_points;
    const Step& a = steps[k - 1];
    const Step& b = steps[k];
    const double t = std::log(a.rms / goal) / std::log(a.rms / b.rms);
    return std::exp(std::log(a.control_points) +
                    t * (std::log(b.control_points) - std::log(a.control_points)));
  }
  return -1.0;
}

std::vector<Step> ladder(const ricci::Mesh& dense, bool adaptive, const Ladder& run,
                         double cholesky) {
  std::vector<Step> steps;
  for (double target = run.first_target; target <= kLastTarget; target *= kStep) {
    spline::FitSurfaceOptions options;
    options.domain_faces = static_cast<int>(std::lround(target));
    options.adaptive_domain = adaptive;
    options.sizing = run.sizing;
    options.refinement_rounds = 0;
    options.fold_rounds = 0;
    const ricci::Stopwatch clock;
    const spline::FittedSurface r = spline::fit_surface(dense, options);
    const double seconds = clock.seconds();
    Step s;
    s.control_points = r.surface.spline.space->function_count();
    s.rms = r.fit_rms / r.bbox_diagonal;
    std::printf("| %s | %d | %d | %d | %.4f%% | %.3f%% | %d | %.1f | %.0f |\n",
                adaptive ? "adaptive" : "uniform", options.domain_faces,
                r.surface.spline.space->domain_face_count(), s.control_points, 100.0 * s.rms,
                100.0 * r.fit_max / r.bbox_diagonal, r.surface_dihedral.over_90_deg, seconds,
                seconds / cholesky);
    std::fflush(stdout);
    steps.push_back(s);
    if (s.rms <= run.goal) break;
  }
  return steps;
}

}  // namespace

int run_adaptive_benchmark(int argc, char** argv) {
  Ladder run;
  double& goal = run.goal;
  std::vector<std::string> models;
  for (int i = 0; i < argc; ++i) {
    const bool value = i + 1 < argc;
    const std::string option = argv[i];
    if (option == "--rms" && value) {
      goal = parse_double(argv[++i], "option " + option);
    } else if (option == "--from" && value) {
      run.first_target = parse_int(argv[++i], "option " + option);
    } else if (option == "--base-share" && value) {
      run.sizing.base_share = parse_double(argv[++i], "option " + option);
    } else if (option == "--max-turn" && value) {
      run.sizing.max_turn_deg = parse_double(argv[++i], "option " + option);
    } else if (option == "--thickness" && value) {
      run.sizing.min_thickness_edges = parse_double(argv[++i], "option " + option);
    } else if (option == "--relax" && value) {
      run.sizing.relax_iterations = parse_int(argv[++i], "option " + option);
    } else if (option == "--by-turn") {
      run.sizing.split_by = spline::AdaptiveDomainOptions::SplitBy::normal_turn;
    } else if (option == "--by-residual") {
      run.sizing.split_by = spline::AdaptiveDomainOptions::SplitBy::quadric_residual;
    } else if (option == "--closest") {
      run.sizing.placement = spline::SplitPlacement::closest_point;
    } else if (option == "--adaptive-only") {
      run.uniform = false;
    } else {
      models.emplace_back(argv[i]);
    }
  }
  if (!(goal > 0.0 && goal < 1.0)) {
    std::fprintf(stderr, "msp-bench adaptive: --rms must be in (0, 1)\n");
    return 2;
  }
  if (run.first_target < 4 || run.first_target > kLastTarget) {
    std::fprintf(stderr, "msp-bench adaptive: --from must be in [4, %d]\n", kLastTarget);
    return 2;
  }
  try {
    if (models.empty()) {
      const std::string shared = shared_models();
      models = {shared + "/closed_g0/venus.off", shared + "/closed_g0/horse.off"};
    }
    std::printf(
        "Adaptive vs uniform domain: fit_surface (no refinement or fold rounds) on domain "
        "targets %d, x%.2f ..., until the RMS of every input vertex to the delivered surface is "
        "below %.3g%% of the diagonal. chol = seconds / one CHOLMOD solve of the scan's "
        "cotangent Laplacian.\n\n",
        run.first_target, kStep, 100.0 * goal);
    for (const std::string& path : models) {
      const ricci::Mesh dense = ricci::read_mesh(path);
      const double cholesky = cotangent_cholesky_seconds(dense);
      std::printf("%s (%zu faces, one Cholesky %.3f s)\n\n", path.c_str(), dense.n_faces(),
                  cholesky);
      std::printf("| domain | target | faces | control points | rms | max | folds | s | chol |\n");
      std::printf("|---|---|---|---|---|---|---|---|---|\n");
      const double uniform =
          run.uniform ? control_points_at(ladder(dense, false, run, cholesky), goal) : -1.0;
      const double adaptive = control_points_at(ladder(dense, true, run, cholesky), goal);
      std::printf(
          "\ncontrol points for %.3g%%: uniform %.0f, adaptive %.0f, adaptive / uniform "
          "%.2f\n\n",
          100.0 * goal, uniform, adaptive, uniform > 0 && adaptive > 0 ? adaptive / uniform : -1.0);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "msp-bench adaptive: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace msp::bench

// msp-bench loop-fit: the OpenSubdiv baseline of issue 5. A Loop subdivision surface with a
// given number of control points fitted to every vertex of each genus 0-3 model; the errors are
// measured as the DMS spline fit measures them (distance of each input vertex to the surface,
// RMS and max over vertices, divided by the input's bounding-box diagonal).
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <ricci/mesh/io.h>
#include <ricci/mesh/primitives.h>
#include <spline/baseline/loop_fit.h>

#include "bench/benchmarks.h"
#include "msp/cli.h"
#include "ricci/util/stopwatch.h"

namespace msp::bench {

namespace {

namespace fs = std::filesystem;
// Every closed genus 0-3 model (OFF/OBJ; horse.ply duplicates horse.off), sorted.
std::vector<std::string> default_models() {
  const fs::path root(shared_models());
  std::vector<std::string> models;
  for (const char* folder : {"closed_g0", "closed_g1", "closed_g2", "closed_g3"}) {
    std::vector<std::string> here;
    for (const auto& entry : fs::directory_iterator(root / folder)) {
      const std::string ext = entry.path().extension().string();
      if (ext == ".off" || ext == ".obj") here.push_back(entry.path().string());
    }
    std::sort(here.begin(), here.end());
    models.insert(models.end(), here.begin(), here.end());
  }
  return models;
}

std::string short_name(const std::string& path) {
  const fs::path p(path);
  return (p.parent_path().filename() / p.filename()).string();
}

}  // namespace

int run_loop_benchmark(int argc, char** argv) {
  std::vector<int> counts = {2000, 20000};
  spline::LoopFitOptions options;
  std::vector<std::string> models;
  for (int i = 0; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--control" && i + 1 < argc) {
      counts = parse_int_list(argv[++i], "option --control");
    } else if (arg == "--smoothness" && i + 1 < argc) {
      options.smoothness = parse_double(argv[++i], "option " + arg);
    } else if (arg == "--corrections" && i + 1 < argc) {
      options.parameter_corrections = parse_int(argv[++i], "option " + arg);
    } else if (arg == "--help") {
      std::printf(
          "msp-bench loop-fit [--control 2000,20000] [--smoothness 1e-3] [--corrections 2] "
          "[models...]\n");
      return 0;
    } else {
      models.push_back(fs::exists(arg) ? arg : shared_models() + "/" + arg);
    }
  }
  if (models.empty()) models = default_models();
  std::printf(
      "Loop subdivision baseline (OpenSubdiv %s, isolation %d, Gregory end caps, lambda %g "
      "relative)\n",
      "3.5", options.isolation_level, options.smoothness);
  std::printf(
      "%d parameter corrections; errors: distance of every input vertex to the limit surface after"
      " %d Gauss-Newton steps, / bbox diagonal\n\n",
      options.parameter_corrections, options.projection_steps);
  std::printf(
      "| model | genus | V | C wanted | C | C/V | RMS/diag | max/diag | RMS/diag at param | wall s "
      "| CPU s | s: simplify/osd/solve/project |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const std::string& path : models) {
    ricci::Mesh dense;
    try {
      dense = ricci::read_mesh(path);
    } catch (const std::exception& e) {
      std::printf("| %s | read failed: %s |\n", short_name(path).c_str(), e.what());
      continue;
    }
    const int genus = ricci::surface_topology(dense).genus;
    for (int count : counts) {
      options.control_points = count;
      const ricci::Stopwatch t0;
      const std::clock_t c0 = std::clock();
      try {
        const spline::LoopFitResult r = spline::fit_loop_surface(dense, options);
        const double seconds = t0.seconds();
        const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
        std::printf(
            "| %s | %d | %zu | %d | %d | %.2f | %.3e | %.3e | %.3e | %.1f | %.1f | "
            "%.1f/%.1f/%.1f/%.1f |\n",
            short_name(path).c_str(), genus, dense.n_vertices(), count, r.control_points,
            r.control_points / static_cast<double>(dense.n_vertices()), r.rms_relative,
            r.max_relative, r.parameter_rms_relative, seconds, cpu, r.seconds_control_mesh,
            r.seconds_surface, r.seconds_solve, r.seconds_projection);
      } catch (const std::exception& e) {
        std::printf("| %s | %d | %zu | %d | failed: %s |\n", short_name(path).c_str(), genus,
                    dense.n_vertices(), count, e.what());
      }
      std::fflush(stdout);
    }
  }
  return 0;
}

}  // namespace msp::bench

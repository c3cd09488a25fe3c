// msp-bench NAME [args]: benchmarks that print figures and ratios (never run as tests).
// Each benchmark lives in its own file; this table is the only place that lists them.
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>

#include "bench/benchmarks.h"

namespace {

struct Benchmark {
  const char* name;
  int (*run)(int, char**);
  const char* summary;
};

const Benchmark kBenchmarks[] = {
    {"flow", msp::bench::run_flow_benchmark,
     "E2 Ricci flow, 1k-1M faces: Newton time, iterations, error, peak memory, ratio to one Cholesky"},
    {"flow-one", msp::bench::run_flow_case,
     "one row of 'flow' in this process (used by 'flow' through a child process)"},
    {"loop-fit", msp::bench::run_loop_benchmark,
     "issue 5 baseline: OpenSubdiv Loop surface fitted to genus 0-3 models, RMS/max per diagonal"},
    {"solvers", msp::bench::run_solver_benchmark,
     "factorisations of the E2 Newton Hessian: Eigen LDLT/LLT vs CHOLMOD supernodal/simplicial"},
    {"spline", msp::bench::run_spline_benchmark,
     "manifold DMS spline at the paper's Table 1 sizes: construction/fit/fair seconds vs T_spline"},
    {"spline-fit", msp::bench::run_spline_fit_benchmark,
     "scan fit on genus 0-3 models [paths...]: RMS/max distance over the diagonal, seconds per stage"},
    {"mesh-io", msp::bench::run_mesh_io_benchmark,
     "read stages (parse, diagnose, build) on the largest shared models vs OpenMesh's reader"},
    {"dms", msp::bench::run_dms_benchmark,
     "DMS triangular B-spline basis, degrees 2..5: DAG build, memory, us per point, PU error"},
    {"singularity", msp::bench::run_singularity_benchmark,
     "automatic singularity: solves, flows, s / one Cholesky [--brute: vs one flow per vertex]"},
    {"fill", msp::bench::run_fill_benchmark,
     "hole filling on fitted scans: per rim edges, seconds, max normal jump, position gaps"},
    {"caps", msp::bench::run_caps_benchmark,
     "issue 19: cap_holes alone on `msp fit --spline` files: seconds, patch unknowns, seam [--runs N]"},
    {"one-cone", msp::bench::run_one_cone_benchmark,
     "issue 8: whole one-cone pipeline per bench/genus 1-3 mesh vs one Cholesky [--million] [--metric M]"
     " [--high-genus: issue 20's genus 3-11 rows, generated genus 4-10 at 10k and 100k faces]"},
    {"one-cone-one", msp::bench::run_one_cone_case, "one row of 'one-cone' in this process"},
    {"atlas-replay", msp::bench::run_atlas_replay,
     "the atlas alone on a metric saved by one-cone-one --save-metric FILE [--polish]"},
    {"intrinsic", msp::bench::run_intrinsic_benchmark,
     "issue 20: one cone by the intrinsic Delaunay flow on genus 4-10 slabs [--faces N,...]"},
    {"topology", msp::bench::run_topology_benchmark,
     "cut graph + slicing on the bench meshes; cut, layout and atlas on flat torus grids"},
    {"eval", msp::bench::run_eval_benchmark,
     "surface evaluation (position, normal, curvatures) us/point; closest-point index and queries"},
    {"bezier", msp::bench::run_bezier_benchmark,
     "Bezier export of a fitted surface: seconds, patches and knot segments per face"},
    {"spline-file", msp::bench::run_spline_file_benchmark,
     "spline file (.msp) of a 4000-face domain fit: size per section, save / load ms vs the fit"},
    {"uniformize", msp::bench::run_uniformize_benchmark,
     "issue 7: uniformization (flow, cut, layout, Fuchsian group) at the Ricci-flow paper's Table I sizes"},
    {"match", msp::bench::run_match_benchmark,
     "issue 17: msp module and msp match at ~20k and ~100k faces [MODELS [CASE...]]"},
    {"fit-scale", msp::bench::run_fit_scale_benchmark,
     "issue 19: msp fit at 1x, 4x, 16x a scan's faces (venus to 1.6M): stages, per M faces, vs one "
     "Cholesky [MESH] [--levels 0,1,2]"},
    {"fit-scale-one", msp::bench::run_fit_scale_case, "one row of 'fit-scale' in this process"},
    {"decimate", msp::bench::run_decimate_benchmark,
     "issue 19: msp fit's own quadric collapse: CPU seconds and a hash of the result [MESH...]\n"
     "      [--faces N] [--levels L] [--repeat R] [--out DIR]"},
    {"adaptive", msp::bench::run_adaptive_benchmark,
     "issue 15: control points for 0.1% RMS, adaptive vs uniform domain (venus, horse) [--rms F]\n"
     "      [--from N] [--base-share F] [--max-turn D] [--thickness E] [--by-turn]\n"
     "      [--by-residual] [--relax N] [--closest] [--adaptive-only]"},
    {"check-glb", msp::bench::run_check_glb,
     "OUT.glb SCAN [--json]: the written surface against the scan, both ways (rms, max, coverage, folds)"},
};

void usage() {
  std::cerr << "usage: msp-bench <name> [args]\n\nbenchmarks:\n";
  for (const auto& b : kBenchmarks) std::cerr << "  " << b.name << "\t" << b.summary << "\n";
  std::cerr << "\nMost benchmarks read the model collection named by the environment variable\n"
               "MSP_SHARED_MODELS (or CMake's -DMSP_SHARED_MODELS=DIR) unless given files.\n";
}

}  // namespace

std::string msp::bench::shared_models() {
  const char* env = std::getenv("MSP_SHARED_MODELS");
  const std::string folder = env != nullptr && *env != '\0' ? env : MSP_SHARED_MODELS_DIR;
  if (folder.empty() || !std::filesystem::is_directory(folder)) {
    throw std::runtime_error(
        "no model collection: set MSP_SHARED_MODELS=DIR (or configure with "
        "-DMSP_SHARED_MODELS=DIR), or pass the meshes as arguments" +
        (folder.empty() ? std::string() : " ('" + folder + "' is not a folder)"));
  }
  return folder;
}

int main(int argc, char** argv) {
  if (argc < 2 || !std::strcmp(argv[1], "--help")) {
    usage();
    return argc < 2 ? 2 : 0;
  }
  for (const auto& b : kBenchmarks) {
    if (std::strcmp(argv[1], b.name) != 0) continue;
    try {
      return b.run(argc - 2, argv + 2);
    } catch (const std::exception& e) {
      std::cerr << "msp-bench " << b.name << ": " << e.what() << "\n";
      return 1;
    }
  }
  std::cerr << "msp-bench: unknown benchmark '" << argv[1] << "'\n";
  usage();
  return 2;
}

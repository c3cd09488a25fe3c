// msp-bench singularity [--brute] [--verification-work W] [MESH...]: the automatic choice of the extraordinary point:
// vertices the linear model scored, its back-substitutions, the real flows run, seconds and
// seconds / one CHOLMOD solve of the cotangent Laplacian of the same mesh; with --brute, against
// the paper's brute force (one full flow per vertex): distortion reached and their ratio.
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <ricci/mesh/io.h>
#include <ricci/singularity/choose.h>

#include "bench/benchmarks.h"
#include "msp/cli.h"
#include "ricci/util/stopwatch.h"

namespace msp::bench {
namespace {

struct BruteForce {
  int vertex = -1;
  double distortion = std::numeric_limits<double>::infinity();
  double seconds = 0;
};

BruteForce brute_force(const ricci::Mesh& mesh) {
  BruteForce best;
  ricci::Stopwatch start;
  for (auto v : mesh.vertices()) {
    double d = ricci::one_cone_area_distortion(mesh, v.idx());
    if (d < best.distortion) {
      best.distortion = d;
      best.vertex = v.idx();
    }
  }
  best.seconds = start.seconds();
  return best;
}

}  // namespace

int run_singularity_benchmark(int argc, char** argv) {
  Args args(argc, argv, {"brute"});
  args.require_known({"brute", "verification-work"});
  ricci::SingularityOptions options;
  if (args.has("verification-work")) options.verification_work = args.get_double("verification-work", 0);
  std::vector<std::string> meshes = args.positionals();
  const bool brute = args.has("brute");
  if (meshes.empty()) {
    const std::string root = shared_models();
    meshes = {root + "/closed_g2/eight_cgal.off", root + "/closed_g2/joint.off",
              root + "/closed_g0/knight_decimated.off", root + "/closed_g3/helmet.off",
              root + "/closed_g2/eight.off"};
  }
  std::printf("| mesh | V | F | chosen | distortion | predicted | ranked | solves | flows | s | "
              "chol s | ratio |%s\n",
              brute ? " brute-force vertex | distortion | flows | s | ratio of distortions |" : "");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|%s\n",
              brute ? "---|---|---|---|---|" : "");
  for (const auto& path : meshes) {
    ricci::Mesh mesh = ricci::read_mesh(path);
    ricci::Stopwatch start;
    ricci::SingularityChoice choice = ricci::choose_singularity(mesh, options);
    const double choice_seconds = start.seconds();
    double distortion = choice.area_distortion;
    if (!std::isfinite(distortion)) distortion = ricci::one_cone_area_distortion(mesh, choice.vertex);
    const double chol = cotangent_cholesky_seconds(mesh);
    std::printf("| %s | %zu | %zu | %d | %.5g | %.5g | %d | %d | %d | %.3f | %.4f | %.1f |",
                path.substr(path.find_last_of('/') + 1).c_str(), mesh.n_vertices(),
                mesh.n_faces(), choice.vertex, distortion, choice.predicted_area_distortion,
                choice.ranked, choice.linear_solves, choice.flows_run, choice_seconds, chol,
                choice_seconds / chol);
    if (brute) {
      const BruteForce b = brute_force(mesh);
      std::printf(" %d | %.5g | %zu | %.1f | %.4f |", b.vertex, b.distortion, mesh.n_vertices(),
                  b.seconds, distortion / b.distortion);
    }
    std::printf("\n");
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace msp::bench

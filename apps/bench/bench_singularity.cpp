// msp-bench singularity [MESH...]: the automatic choice of the extraordinary point against the
// paper's brute force (one full flow per vertex): distortion reached, flows run, seconds, ratio.
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <ricci/mesh/io.h>
#include <ricci/singularity/choose.h>

#include "bench/benchmarks.h"
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
  std::vector<std::string> meshes;
  for (int i = 0; i < argc; ++i) meshes.emplace_back(argv[i]);
  if (meshes.empty()) {
    const std::string root = shared_models();
    meshes = {root + "/closed_g2/eight_cgal.off", root + "/closed_g2/joint.off", root + "/closed_g0/knight_decimated.off",
              root + "/closed_g3/helmet.off", root + "/closed_g2/eight.off"};
  }
  std::printf("| mesh | V | F | chosen | distortion | flows | s | brute-force vertex | distortion | flows | s | ratio of distortions | speed-up |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const auto& path : meshes) {
    ricci::Mesh mesh = ricci::read_mesh(path);
    ricci::Stopwatch start;
    ricci::SingularityChoice choice = ricci::choose_singularity(mesh);
    double choice_seconds = start.seconds();
    BruteForce brute = brute_force(mesh);
    std::printf("| %s | %zu | %zu | %d | %.5g | %d | %.3f | %d | %.5g | %zu | %.3f | %.4f | %.1fx |\n",
                path.substr(path.find_last_of('/') + 1).c_str(), mesh.n_vertices(), mesh.n_faces(), choice.vertex,
                choice.area_distortion, choice.flows_run, choice_seconds, brute.vertex, brute.distortion,
                mesh.n_vertices(), brute.seconds, choice.area_distortion / brute.distortion,
                brute.seconds / choice_seconds);
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace msp::bench

// msp-bench decimate [MESH...] [--faces N] [--levels L] [--repeat R] [--out DIR] [--whole]
// [--regions K]: the library's quadric edge collapse (ricci::quadric_decimate, the first stage of
// msp fit's simplification, with K regions, 0 = its default; --whole: all of ricci::simplify_mesh,
// msp fit's simplify stage, to N faces) on each mesh: seconds and CPU seconds (best of R runs) and
// a hash of the result's vertex bits and faces, so that a faster decimation can be checked to
// collapse exactly the same edges (issue 19).

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <ricci/mesh/io.h>
#include <ricci/mesh/simplify.h>
#include <ricci/mesh/simplify_quadric.h>
#include <ricci/util/hash.h>
#include <ricci/util/stopwatch.h>

#include "bench/benchmarks.h"
#include "bench/child_run.h"
#include "msp/cli.h"

namespace msp::bench {
namespace {

// FNV-1a over the vertex count, every coordinate's bits and every face's vertex indices.
std::uint64_t mesh_hash(const ricci::Mesh& mesh) {
  ricci::Fnv1a hash;
  const auto mix = [&hash](const void* data, size_t size) { hash.add_bytes(data, size); };
  const std::uint64_t vertices = mesh.n_vertices();
  mix(&vertices, sizeof vertices);
  for (auto v : mesh.vertices()) mix(mesh.point(v).data(), 3 * sizeof(double));
  for (auto f : mesh.faces()) {
    for (auto v : mesh.fv_range(f)) {
      const int index = v.idx();
      mix(&index, sizeof index);
    }
  }
  return hash.value();
}

}  // namespace

int run_decimate_benchmark(int argc, char** argv) {
  Args args(argc, argv, {"whole"});
  args.require_known({"faces", "levels", "repeat", "out", "whole", "regions"});
  std::vector<std::string> files = args.positionals();
  if (files.empty()) {
    const std::string models = shared_models();
    for (const char* name : {"closed_g0/venus.off", "closed_g0/horse.off", "closed_g3/block.off",
                             "closed_g2/joint.off", "closed_g3/helmet.off", "bench/genus2_100k.obj"})
      files.push_back(models + "/" + name);
  }
  const bool whole = args.has("whole");
  // msp fit's domain, else the first stage's size at that domain
  const int target = args.get_int("faces", whole ? 2000 : 16000);
  const int levels = args.get_int("levels", 0);
  const int repeat = std::max(1, args.get_int("repeat", 1));
  const std::string out = args.get_or("out", "");
  ricci::QuadricDecimateOptions decimate;
  decimate.regions = args.get_int("regions", 0);
  std::printf("%s to %d faces (inputs refined %d times and displaced as in "
              "fit-scale when L > 0); cpu: CPU seconds, best of %d; hash: FNV-1a of the result's "
              "vertex bits and faces; seconds: wall of the same run\n",
              whole ? "ricci::simplify_mesh" : "ricci::quadric_decimate", target, levels, repeat);
  std::printf("%-22s %9s %8s %8s %8s %18s\n", "mesh", "faces", "after", "seconds", "cpu",
              "hash");
  for (const std::string& path : files) {
    const ricci::Mesh input = levels > 0 ? refined_scan(path, levels, 2e-4) : ricci::read_mesh(path);
    ricci::Mesh decimated;
    double best = 1e300, wall = 0.0;
    for (int run = 0; run < repeat; ++run) {
      const ricci::CpuStopwatch cpu_clock;
      const ricci::Stopwatch wall_clock;
      if (whole) {
        ricci::SimplifyOptions options;
        options.target_faces = target;
        decimated = ricci::simplify_mesh(input, options).mesh;
      } else {
        decimated = input;
        ricci::quadric_decimate(decimated, target, decimate);
      }
      const double cpu = cpu_clock.seconds();
      if (cpu < best) {
        best = cpu;
        wall = wall_clock.seconds();
      }
    }
    const std::string name = case_label(path, levels);
    std::printf("%-22s %9zu %8zu %8.3f %8.3f %016llx\n", name.c_str(), input.n_faces(),
                decimated.n_faces(), wall, best,
                static_cast<unsigned long long>(mesh_hash(decimated)));
    if (!out.empty()) {
      const std::string file = path.substr(path.find_last_of('/') + 1);
      ricci::write_mesh(decimated, out + "/" + file.substr(0, file.find('.')) + ".off");
    }
  }
  return 0;
}

}  // namespace msp::bench

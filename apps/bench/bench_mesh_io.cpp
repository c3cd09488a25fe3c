// msp-bench mesh-io [FILE...]: time of each stage of reading a mesh (file bytes, parse, diagnose,
// build the OpenMesh surface) on the largest shared models, against OpenMesh's own reader.
// Figures are the best of 3 runs, in milliseconds of wall time.
#include <OpenMesh/Core/IO/MeshIO.hh>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <ricci/mesh/build_mesh.h>
#include <ricci/mesh/diagnose.h>
#include <ricci/mesh/parse_util.h>
#include <ricci/mesh/soup_io.h>

#include "bench/benchmarks.h"
#include "ricci/util/stopwatch.h"

namespace msp::bench {
namespace {

template <typename Function>
double best_ms(Function&& run) {
  double best = 1e300;
  for (int trial = 0; trial < 3; ++trial) {
    const ricci::Stopwatch watch;
    run();
    best = std::min(best, 1e3 * watch.seconds());
  }
  return best;
}

}  // namespace

int run_mesh_io_benchmark(int argc, char** argv) {
  std::vector<std::string> files(argv, argv + argc);
  if (files.empty()) {
    const std::string models = shared_models();
    for (const char* name :
         {"closed_g0/venus.off", "closed_g0/armadillo.obj", "closed_g0/horse.ply",
          "open/stanford-bunny.obj", "bench/genus3_100k.obj"})
      files.push_back(models + "/" + name);
  }
  std::printf("%-28s %8s %8s %8s %9s %8s %10s %9s\n", "file", "faces", "bytes", "parse", "diagnose",
              "build", "openmesh", "ratio");
  for (const auto& path : files) {
    std::string bytes;
    ricci::PolygonSoup soup;
    const double read = best_ms([&] { bytes = ricci::detail::read_file_bytes(path); });
    const auto format = ricci::format_from_extension(path);
    const double parse = best_ms([&] { soup = ricci::parse_soup(bytes, format, path); });
    const double diagnose = best_ms([&] { (void)ricci::diagnose(soup); });
    const double build = best_ms([&] { (void)ricci::build_mesh(soup); });
    const double openmesh = best_ms([&] {
      ricci::Mesh mesh;
      OpenMesh::IO::read_mesh(mesh, path);
    });
    const double ours = read + parse + diagnose + build;
    const std::string name = path.substr(path.find_last_of('/') + 1);
    std::printf("%-28s %8zu %7.1fM %8.1f %9.1f %8.1f %10.1f %8.2fx\n", name.c_str(),
                soup.faces.size(), bytes.size() / 1e6, read + parse, diagnose, build, openmesh,
                ours / openmesh);
  }
  std::printf(
      "(ms, best of 3; parse includes reading the bytes; build runs diagnose again;\n"
      " ratio = (parse + diagnose + build) / OpenMesh::IO::read_mesh)\n");
  return 0;
}

}  // namespace msp::bench

// msp-bench caps: cap_holes (spline/surface/cap_holes.h) alone on spline files that `msp fit
// --spline OUT.msp` saved: the saved patches are dropped and the rims capped again, as
// fit_surface caps a closed scan's delivered round (cone_hole_limits of the domain's genus).
// Per run: wall and CPU seconds, the patches' triangles and unknowns, the largest seam.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "bench/benchmarks.h"
#include "msp/cli.h"
#include "ricci/util/stopwatch.h"
#include "spline/io/spline_file.h"
#include "spline/surface/cap_holes.h"

namespace msp::bench {

int run_caps_benchmark(int argc, char** argv) {
  int runs = 3;
  std::vector<std::string> files;
  for (int i = 0; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--runs" && i + 1 < argc)
      runs = parse_int(argv[++i], "option " + arg);
    else
      files.push_back(arg);
  }
  if (files.empty()) {
    std::fprintf(stderr, "usage: msp-bench caps FILE.msp... [--runs N]\n");
    return 2;
  }
  int failed = 0;
  for (const std::string& path : files) {
    try {
      const spline::SplineSurface saved = spline::load_spline_surface(path);
      const ricci::Mesh& mesh = saved.domain;
      const long euler = static_cast<long>(mesh.n_vertices()) -
                         static_cast<long>(mesh.n_edges()) + static_cast<long>(mesh.n_faces());
      const int genus = static_cast<int>((2 - euler) / 2);
      spline::CapHolesOptions options;
      options.cone_hole = spline::cone_hole_limits(genus);
      std::printf("%s: genus %d, %zu domain faces\n", path.c_str(), genus, mesh.n_faces());
      std::printf("  run   wall s    CPU s  patches  triangles  unknowns  seam deg\n");
      for (int run = 0; run < runs; ++run) {
        spline::SplineSurface surface = saved;
        surface.fills.clear();
        surface.open_rims.clear();
        ricci::StageTimer timer;
        const spline::CapHolesReport report = spline::cap_holes(surface, options);
        const double wall = timer.wall.seconds(), cpu = timer.cpu.seconds();
        int triangles = 0, unknowns = 0;
        for (const auto& fill : surface.fills) {
          triangles += fill.space->triangle_count();
          unknowns += fill.space->function_count();
        }
        std::printf("  %3d %8.3f %8.3f %8zu %10d %9d %9.4f\n", run, wall, cpu,
                    surface.fills.size(), triangles, unknowns, report.max_normal_jump_deg);
      }
    } catch (const std::exception& e) {
      std::fprintf(stderr, "msp-bench caps: %s\n", e.what());
      ++failed;
    }
  }
  return failed > 0 ? 1 : 0;
}

}  // namespace msp::bench

// msp-bench spline-file [MESH...] [--domain-faces N]: the spline file (spline/io/spline_file.h)
// of fit_surface's surface at a 4000-face domain (before the cone refinement): file size and
// its largest sections, save (encode + atomic write) and load (read + decode, which rebuilds and
// checks the spaces) in milliseconds, best of 3, and the fit they replace. Default mesh: the
// shared bench/genus3_100k.obj.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <ricci/mesh/io.h>
#include <spline/io/spline_file.h>
#include <spline/surface/fit_surface.h>

#include "bench/benchmarks.h"
#include "msp/cli.h"

namespace msp::bench {
namespace {

using Clock = std::chrono::steady_clock;

template <typename Function>
double best_ms(Function&& run) {
  double best = 1e300;
  for (int trial = 0; trial < 3; ++trial) {
    const auto start = Clock::now();
    run();
    best = std::min(best, std::chrono::duration<double, std::milli>(Clock::now() - start).count());
  }
  return best;
}

// "MESH 0.1M ATLS 1.2M ...": each section's payload in megabytes (docs/spline-file.md).
std::string section_sizes(const std::vector<std::uint8_t>& bytes) {
  const auto u64_at = [&](std::size_t at) {
    std::uint64_t value = 0;
    for (int i = 0; i < 8; ++i) value |= static_cast<std::uint64_t>(bytes[at + i]) << (8 * i);
    return value;
  };
  std::size_t at = 16 + static_cast<std::size_t>(u64_at(12) & 0xffffffffu);
  std::string out;
  char item[64];
  while (at + 12 <= bytes.size()) {
    const std::uint64_t length = u64_at(at + 4);
    std::snprintf(item, sizeof item, "%.4s %.2fM ", reinterpret_cast<const char*>(&bytes[at]),
                  static_cast<double>(length) / 1e6);
    if (length > 0) out += item;
    at += 12 + static_cast<std::size_t>(length);
  }
  return out;
}

}  // namespace

int run_spline_file_benchmark(int argc, char** argv) {
  Args args(argc, argv, {});
  args.require_known({"domain-faces"});
  std::vector<std::string> meshes = args.positionals();
  if (meshes.empty())
    meshes.push_back(std::string(MSP_SHARED_MODELS_DIR) + "/bench/genus3_100k.obj");
  spline::FitSurfaceOptions options;
  options.domain_faces = args.get_int("domain-faces", 4000);
  const std::string path =
      (std::filesystem::temp_directory_path() / "msp_bench_spline_file.msp").string();
  std::printf("%-20s %7s %8s %5s %9s %8s %8s %8s %8s %8s  %s\n", "mesh", "faces", "ctrl", "fills",
              "patch_fn", "MB", "encode", "save", "decode", "load", "fit s");
  for (const std::string& mesh_path : meshes) {
    const auto start = Clock::now();
    const spline::FittedSurface fitted = spline::fit_surface(ricci::read_mesh(mesh_path), options);
    const double fit_seconds = std::chrono::duration<double>(Clock::now() - start).count();
    const spline::SplineSurface& surface = fitted.surface;
    long patch_functions = 0;
    for (const auto& fill : surface.fills) patch_functions += fill.space->function_count();
    std::vector<std::uint8_t> bytes;
    const double encode = best_ms([&] { bytes = spline::encode_spline_surface(surface); });
    const double save = best_ms([&] { spline::save_spline_surface(surface, path); });
    const double decode = best_ms([&] { (void)spline::decode_spline_file(bytes, "bench"); });
    const double load = best_ms([&] { (void)spline::load_spline_surface(path); });
    const std::string name = mesh_path.substr(mesh_path.find_last_of('/') + 1);
    std::printf("%-20s %7zu %8ld %5zu %9ld %8.2f %8.1f %8.1f %8.1f %8.1f  %.1f\n", name.c_str(),
                surface.domain.n_faces(), static_cast<long>(surface.spline.control_points.rows()),
                surface.fills.size(), patch_functions, static_cast<double>(bytes.size()) / 1e6,
                encode, save, decode, load, fit_seconds);
    std::printf("  sections: %s\n", section_sizes(bytes).c_str());
  }
  std::filesystem::remove(path);
  std::printf(
      "(faces: the domain after the cone refinement; patch_fn: functions of the fill patches;\n"
      " ms, best of 3; save = encode + atomic write, load = read + decode (spaces rebuilt and\n"
      " checked); fit s: fit_surface, the job a load replaces)\n");
  return 0;
}

}  // namespace msp::bench

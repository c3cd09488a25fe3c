// msp-bench check-glb OUT.glb SCAN [--json]: the delivered surface measured from outside, as a
// user would: the .glb's "surface" mesh read back (float32, welded by value), every scan vertex
// to it and points of it back to the scan by global closest-point queries, coverage, boundary
// distance and folds. The figures `msp fit`'s report must agree with.
#include <array>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <ricci/mesh/arrays.h>
#include <ricci/mesh/io.h>
#include <spline/tessellate/dihedral.h>
#include <spline/tessellate/scan_distance.h>

#include "bench/benchmarks.h"
#include "msp/io/gltf_reader.h"

namespace msp::bench {

int run_check_glb(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: msp-bench check-glb OUT.glb SCAN [--json]\n";
    return 2;
  }
  const bool json = argc > 2 && std::strcmp(argv[2], "--json") == 0;
  const auto surface = gltf::read_glb_triangles(argv[0]);
  const auto scan = ricci::to_arrays(ricci::read_mesh(argv[1]));
  std::vector<std::array<int, 3>> scan_triangles(static_cast<std::size_t>(scan.F.rows()));
  for (Eigen::Index f = 0; f < scan.F.rows(); ++f) {
    scan_triangles[static_cast<std::size_t>(f)] = {scan.F(f, 0), scan.F(f, 1), scan.F(f, 2)};
  }
  const auto d = spline::measure_against_scan(surface.positions, surface.triangles, scan.V,
                                              scan_triangles);
  const auto folds = spline::dihedral_angles(surface.triangles, surface.positions);
  const double diag = d.bbox_diagonal;
  const auto pct = [&](double x) { return x < 0.0 ? x : 100.0 * x / diag; };
  nlohmann::json out = {
      {"glb", argv[0]},
      {"scan", argv[1]},
      {"scan_vertices", d.scan_points},
      {"fit_rms_pct", pct(d.fit_rms)},
      {"fit_max_pct", pct(d.fit_max)},
      {"surface_points", d.surface_points},
      {"surface_to_scan_p99_pct", pct(d.surface_to_scan_p99)},
      {"surface_to_scan_max_pct", pct(d.surface_to_scan_max)},
      {"coverage", d.coverage},
      {"boundary_hausdorff_pct", pct(d.boundary_hausdorff)},
      {"surface_boundary_to_scan_boundary_pct", pct(d.surface_boundary_to_scan_boundary)},
      {"scan_boundary_to_surface_boundary_pct", pct(d.scan_boundary_to_surface_boundary)},
      {"boundary_hausdorff_point",
       {d.boundary_hausdorff_point.x(), d.boundary_hausdorff_point.y(),
        d.boundary_hausdorff_point.z()}},
      {"folds_over_90_deg", folds.over_90_deg},
      {"surface_triangles", surface.triangles.size()},
  };
  if (json) {
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  std::printf("%-40s rms %.3f%%  max %.3f%%  s2s p99 %.3f%% max %.3f%%  cover %.4f  bnd %.3f%%  "
              "folds %d\n",
              argv[0], pct(d.fit_rms), pct(d.fit_max), pct(d.surface_to_scan_p99),
              pct(d.surface_to_scan_max), d.coverage, pct(d.boundary_hausdorff),
              folds.over_90_deg);
  return 0;
}

}  // namespace msp::bench

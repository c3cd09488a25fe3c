// msp-bench fill: hole filling (spline/fill/hole_fill.h) on fitted scans: per rim its kind, edge
// count, covered faces, seconds, max normal jump (degrees, 100 samples per rim edge) and the
// position gaps over the bounding-box diagonal; a rim that cannot be filled prints the reason.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "bench/benchmarks.h"
#include "msp/cli.h"
#include "ricci/mesh/io.h"
#include "ricci/util/stopwatch.h"
#include "spline/fill/hole_fill.h"
#include "spline/fill/meet_patch.h"
#include "spline/fill/rims.h"
#include "spline/fit/fit.h"

namespace msp::bench {
namespace {

std::vector<std::string> default_models() {
  std::vector<std::string> models;
  const std::string shared = shared_models();
  for (const char* dir : {"closed_g0", "closed_g1", "closed_g2", "closed_g3", "open"}) {
    std::vector<std::string> found;
    for (const auto& entry : std::filesystem::directory_iterator(shared + "/" + dir)) {
      if (entry.path().extension() != ".ply") found.push_back(entry.path().string());
    }
    std::sort(found.begin(), found.end());
    models.insert(models.end(), found.begin(), found.end());
  }
  return models;
}

// Angle (degrees) between two unit normals; atan2 stays accurate for tiny angles.
double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI;
}

// The fitted surface's own roughness at the knot clouds' scale, by ring from the domain's rim
// (domain_rim_rings; 7 = 7 or more): per face, the largest normal turn between consecutive
// 1/100 steps along its three edges (just inside the face); median, 90th percentile and max.
void print_surface_steps(const spline::ScanFitResult& fit) {
  const auto& space = *fit.spline.space;
  const std::vector<int> rings = spline::domain_rim_rings(space);
  constexpr int kRings = 8;
  std::vector<std::vector<double>> by_ring(kRings);
  for (int d = 0; d < space.domain_face_count(); ++d) {
    const int face = space.domain_faces()[d];
    double worst = 0.0;
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d previous = Eigen::Vector3d::Zero();
      for (int i = 0; i <= 100; ++i) {
        Eigen::Vector3d bary = Eigen::Vector3d::Zero();
        bary[(k + 1) % 3] = 1.0 - i / 100.0;
        bary[(k + 2) % 3] = i / 100.0;
        bary = 0.999 * bary + Eigen::Vector3d::Constant(0.001 / 3.0);
        const Eigen::Vector3d normal = fit.spline.evaluate({face, bary}).normal;
        if (i > 0) worst = std::max(worst, angle_deg(normal, previous));
        previous = normal;
      }
    }
    by_ring[std::clamp(rings[d], 0, kRings - 1)].push_back(worst);
  }
  for (int r = 0; r < kRings; ++r) {
    auto& steps = by_ring[r];
    if (steps.empty()) continue;
    std::sort(steps.begin(), steps.end());
    std::printf(
        "   ring %d%s: %4zu faces, normal step per 1/100 edge median %.3f p90 %.3f max %.3f\n", r,
        r == kRings - 1 ? "+" : " ", steps.size(), steps[steps.size() / 2],
        steps[steps.size() * 9 / 10], steps.back());
  }
}

struct FillBenchFlags {
  bool per_edge = false;       ///< worst jump and surface normal step per rim edge
  bool surface_steps = false;  ///< print_surface_steps
};

void fill_model(const std::string& path, const spline::ScanFitOptions& fit_options,
                const spline::FindRimsOptions& rim_options,
                const spline::FillOptions& fill_options, const FillBenchFlags& flags) {
  const std::string name = std::filesystem::path(path).filename().string();
  const ricci::Stopwatch start;
  spline::ScanFitResult fit;
  try {
    fit = spline::fit_scan(ricci::read_mesh(path), fit_options);
  } catch (const std::exception& e) {
    std::printf("%-28s fit failed: %s\n", name.c_str(), e.what());
    return;
  }
  const double fit_seconds = start.seconds();
  const auto& mesh = fit.atlas.problem.mesh;
  if (flags.surface_steps) print_surface_steps(fit);
  // As msp fit: the cone hole also grows past faces where the spline folds.
  const auto& space = *fit.spline.space;
  std::vector<char> in_domain(mesh.n_faces(), 0);
  for (int f = 0; f < space.face_count(); ++f) in_domain[f] = space.in_domain(f) ? 1 : 0;
  const auto rims = spline::find_rims(
      mesh, in_domain, space.atlas().in_domain, rim_options, {},
      spline::chart_scale_by_face(space, mesh),
      [&fit](int face) { return spline::max_normal_step_deg(fit.spline, face); });
  if (rims.empty()) std::printf("%-28s fit %5.1fs  no rims\n", name.c_str(), fit_seconds);
  std::vector<spline::HoleFill> fills;
  for (const auto& rim : rims) {
    const ricci::Stopwatch t;
    std::printf("%-28s fit %5.1fs  %-9s %5zu %6zu", name.c_str(), fit_seconds,
                spline::rim_kind_id(rim.kind), rim.edges.size(), rim.covered_faces.size());
    try {
      const auto fill = spline::fill_rim(fit.spline, mesh, rim, fill_options);
      std::printf(" %6.2f %9.4f %10.2e %10.2e %6d %s\n", t.seconds(), fill.max_normal_jump_deg,
                  fill.max_position_gap, fill.rms_position_gap, fill.space->triangle_count(),
                  fill.g1 ? "G1" : "C0 fallback");
      fills.push_back(fill);
      if (flags.per_edge) {
        for (std::size_t j = 0; j < rim.edges.size(); ++j) {
          double worst = 0, worst_t = 0, change = 0, change_t = 0;
          Eigen::Vector3d previous = Eigen::Vector3d::Zero();
          for (int i = 0; i <= 100; ++i) {
            const double tt = i / 100.0;
            const auto e = rim.edges[j];
            const auto sj = fit.spline.evaluate({e.face, spline::rim_edge_barycentric(e, tt)});
            const auto p = fill.evaluate(fill.parameter(static_cast<int>(j), tt));
            const double a = angle_deg(sj.normal, p.normal);
            if (a > worst) {
              worst = a;
              worst_t = tt;
            }
            const double c = i > 0 ? angle_deg(sj.normal, previous) : 0.0;
            if (c > change) {
              change = c;
              change_t = tt;
            }
            previous = sj.normal;
          }
          std::printf("   edge %zu worst %.3f at t %.2f  surface normal step max %.3f at %.2f\n", j,
                      worst, worst_t, change, change_t);
        }
      }
    } catch (const std::exception& e) {
      std::printf(" %6.2f  not filled: %s\n", t.seconds(), e.what());
    }
  }
  if (fills.empty()) return;
  // What msp fit shows: the surface moved to meet the patches (meet_patch.h).
  const ricci::Stopwatch t;
  spline::ManifoldSpline met = fit.spline;
  spline::MeetPatchResult result = spline::meet_patches(fit.spline, fills);
  met.control_points = std::move(result.control_points);
  for (std::size_t i = 0; i < fills.size(); ++i) {
    const spline::SeamReport seam =
        result.seams.empty() ? spline::measure_seam(met, fills[i]) : result.seams[i];
    std::printf("%-28s   after meet_patches: rim %zu jump_deg %.4f max_gap %.2e (%.2fs)\n",
                name.c_str(), i, seam.max_normal_jump_deg, seam.max_position_gap, t.seconds());
  }
}

}  // namespace

int run_fill_benchmark(int argc, char** argv) {
  spline::ScanFitOptions fit_options;
  fit_options.domain_faces = 1000;
  spline::FindRimsOptions rim_options;
  spline::FillOptions fill_options;
  std::vector<std::string> models;
  FillBenchFlags flags;
  for (int i = 0; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--faces" && i + 1 < argc)
      fit_options.domain_faces = parse_int(argv[++i], "option " + arg);
    else if (arg == "--grow" && i + 1 < argc)
      rim_options.grow = parse_int(argv[++i], "option " + arg);
    else if (arg == "--refinement" && i + 1 < argc)
      fill_options.refinement = parse_int(argv[++i], "option " + arg);
    else if (arg == "--corner-refinement" && i + 1 < argc)
      fill_options.corner_refinement = parse_int(argv[++i], "option " + arg);
    else if (arg == "--samples" && i + 1 < argc)
      fill_options.fit_samples_per_edge = parse_int(argv[++i], "option " + arg);
    else if (arg == "--method" && i + 1 < argc) {
      const std::string m = argv[++i];
      fill_options.method = m == "height"       ? spline::FillMethod::height_field
                            : m == "parametric" ? spline::FillMethod::parametric
                                                : spline::FillMethod::automatic;
    } else if (arg == "--cross" && i + 1 < argc)
      fill_options.cross_weight = parse_double(argv[++i], "option " + arg);
    else if (arg == "--tangent" && i + 1 < argc)
      fill_options.tangent_weight = parse_double(argv[++i], "option " + arg);
    else if (arg == "--max-boundary" && i + 1 < argc)
      fill_options.max_boundary_vertices = parse_int(argv[++i], "option " + arg);
    else if (arg == "--per-edge")
      flags.per_edge = true;
    else if (arg == "--surface-steps")
      flags.surface_steps = true;
    else if (arg == "--fill-boundaries")
      fill_options.fallback_boundary = true;
    else if (arg == "--smoothing" && i + 1 < argc)
      fill_options.smoothing = parse_double(argv[++i], "option " + arg);
    else
      models.push_back(arg);
  }
  if (models.empty()) models = default_models();
  std::printf(
      "Hole filling: fit_scan (~%d domain faces), find_rims (grow %d), fill_rim (refinement "
      "%d, corner refinement %d, %d fit samples per edge, smoothing %g);\njump: max normal angle (deg) at 100 samples "
      "per rim edge; gaps |P - S| / bbox diagonal; wall seconds.\noptions: --faces N --grow G "
      "--refinement R --corner-refinement C --samples Q --smoothing S --method auto|height|parametric --cross W "
      "--tangent W --max-boundary B --per-edge (worst jump and surface normal step per rim "
      "edge) --surface-steps (the surface's normal step per 1/100 edge by ring from the rim) "
      "--fill-boundaries (fallback for boundary loops) "
      "[models...]\n\n",
      fit_options.domain_faces, rim_options.grow, fill_options.refinement,
      fill_options.corner_refinement, fill_options.fit_samples_per_edge, fill_options.smoothing);
  std::printf("%-28s %10s %-9s %5s %6s %6s %9s %10s %10s %6s %s\n", "model", "", "rim", "edges",
              "cover", "s", "jump_deg", "max_gap", "rms_gap", "tris", "patch");
  for (const auto& path : models) fill_model(path, fit_options, rim_options, fill_options, flags);
  return 0;
}

}  // namespace msp::bench

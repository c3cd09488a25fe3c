#pragma once
// The whole `msp fit` job on a mesh in memory: the scan fit of libspline (simplify, one-cone
// atlas, space, parameters, fit, fair), hole filling, watertight tessellation and the figures
// that say whether it worked (distance to the scan, seam normal jumps, topology of the result).
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <ricci/mesh/mesh.h>
#include <ricci/mesh/primitives.h>
#include <spline/fit/fit.h>
#include <spline/tessellate/dihedral.h>
#include <spline/tessellate/tessellate.h>
#include <nlohmann/json.hpp>

namespace msp {

struct FitRunOptions {
  int domain_faces = 2000;  ///< Target size of the spline's domain mesh.
  int degree = 3;           ///< n of the DMS spline.
  int fairness = 1;         ///< r of the fairing (-1: none).
  /// Weight of the fit's thin-plate energy (spline::FitOptions::smoothing).
  double smoothing = spline::FitOptions{}.smoothing;
  /// Input-mesh vertex of the extraordinary point, -1 to choose it (least area distortion).
  int singular_vertex = -1;
  bool fill_boundaries = false;  ///< Also cap the input's own boundary loops.
  int density = 0;               ///< Samples per domain edge - 1; 0 = chosen by domain size.
  /// Denser sampling around the cone (levels 0: off).
  ricci::ConeRefinementOptions cone_refinement = spline::ScanFitOptions{}.atlas.cone_refinement;
  /// Called with a stage name when the stage starts (the stage names of `seconds`).
  std::function<void(const std::string& stage)> progress;
};

struct FitFills;

struct FitRun {
  ricci::SurfaceTopology input;  ///< Of the input mesh.
  spline::ScanFitResult scan;
  int singular_domain_vertex = -1;  ///< Vertex of the domain (simplified) mesh, -1 when none.
  std::shared_ptr<FitFills> fills;  ///< The rims and their patches (msp/fit_fill.h).
  std::vector<std::string> fill_failures;  ///< Rims whose fill was refused, with the reason.
  spline::Tessellation tessellation;
  spline::WatertightReport topology;  ///< Of the tessellation (position indices).
  /// Of the tessellation as a file holds it: positions rounded to float and welded by value (a
  /// surface that collapses somewhere shows degenerate triangles here, not in `topology`).
  spline::WatertightReport float_topology;
  /// Angles between adjacent triangles of the tessellation (folds show as > 90 degrees).
  spline::DihedralReport surface_dihedral;
  int filled_rims = 0;
  int open_rims = 0;  ///< Rims left open (boundaries without --fill-boundaries, failures).
  /// Rims along the input's boundary loops: with --fill-boundaries fewer than its loops where
  /// loops a ring or two apart merged into one hole (spline/fill/rims.h); without, one per loop.
  int boundary_rims = 0;
  int fallback_fills = 0;  ///< Filled rims whose patch is the positions-only fallback (not G1).
  /// Manifold (as computed and as float32 welded by value) of the input's genus, with one
  /// boundary loop per rim left open on purpose (a failed fill leaves one more: not watertight).
  bool watertight = false;
  double fit_rms = 0.0, fit_max = 0.0;  ///< Input vertices to the spline (projection).
  int fit_points = 0;                   ///< Input vertices measured.
  int fit_points_on_fills = 0;          ///< Of those, measured against a fill patch.
  double bbox_diagonal = 0.0;           ///< Of the input.
  double edge_normal_jump_deg = 0.0;    ///< Across domain edges (the spline's own seams).
  double fill_normal_jump_deg = 0.0;    ///< Across the rims of the fill patches.
  double fill_position_gap = 0.0;       ///< Largest gap patch - spline over the domain diagonal.
  /// Wall-clock seconds by stage, in the order run (read and write are the caller's).
  std::vector<std::pair<std::string, double>> seconds;
  /// CPU seconds of the process (all threads) by stage: on a shared machine the wall clock
  /// includes waiting for a core, this does not.
  std::vector<std::pair<std::string, double>> cpu_seconds;
};

/// Minimum --domain-faces for a surface of this genus: the domain must hold the cone's star,
/// the cut graph's 2g loops and a vertex chart around each, a few hundred faces at least.
[[nodiscard]] int minimum_domain_faces(int genus);

/// Runs the pipeline. \throw ricci::InvalidInputError for a singular vertex out of range or on
/// the boundary, or too few domain faces; as spline::fit_scan otherwise.
[[nodiscard]] FitRun run_fit_pipeline(const ricci::Mesh& dense, const FitRunOptions& options);

/// The report of issue 6: genus, singularities, domain_faces, control_points, degree,
/// fairness, fit_rms, fit_max, bbox_diagonal, seam_normal_jump_max_deg, watertight, seconds
/// (per stage and total), plus the figures behind them.
[[nodiscard]] nlohmann::json fit_report_json(const std::string& path, const FitRun& run,
                                             const FitRunOptions& options);

}  // namespace msp

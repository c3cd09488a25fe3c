#pragma once
// The hole-filling stage of fit_surface: which rims of a fitted spline are capped by patches
// (fill/hole_fill.h), with which fill options and retries, and the spline moved to meet the
// patches (fill/meet_patch.h).
#include <atomic>
#include <string>
#include <vector>

#include "spline/fill/hole_fill.h"
#include "spline/surface/spline_surface.h"

namespace spline {

/// How far the cone hole may grow past badly conditioned or folded faces
/// (FindRimsOptions::max_cone_layers, max_cone_cover_fraction).
struct ConeHoleLimits {
  int max_layers = FindRimsOptions{}.max_cone_layers;
  double max_cover_fraction = FindRimsOptions{}.max_cone_cover_fraction;
  /// FindRimsOptions::cone_margin_layers
  int margin_layers = FindRimsOptions{}.cone_margin_layers;
  int reach_layers = FindRimsOptions{}.cone_reach_layers;  ///< FindRimsOptions::cone_reach_layers
  /// FindRimsOptions::cone_reach_cover_fraction
  double reach_cover_fraction = FindRimsOptions{}.cone_reach_cover_fraction;
  /// Retries of a cone patch whose seam misses FillOptions::target_jump_deg (and is no flip):
  /// the faces around the ends of its worst rim edges (those above a quarter of the largest
  /// jump) join the hole (FindRimsOptions::cone_rim_vertices_to_cover); a retry is kept only
  /// when the seam drops. Each retry costs one fill_rim. 0: none.
  int vertex_rounds = 0;
  /// The cone holes tried (reach or caps, flip retries, vertex rounds) are compared by their
  /// patches on a uniform grid (FillOptions::corner_refinement 1), and only the chosen hole is
  /// filled again with the corner-refined patch (kept when its seam is smaller): one
  /// corner-refined patch per capping instead of 4-6.
  bool compare_uniform = false;
};

/// The limits for the one-cone surface of this genus: FindRimsOptions' up to genus 3; from
/// genus 4 (a cone of 2 pi (2g - 1) >= 14 pi, around which the flat metric scales like
/// rho^(2g - 2)) 8 layers and a quarter of the domain, since the rings where neighbouring
/// charts differ in scale by more than max_cone_rim_scale_ratio reach farther, and 2 vertex
/// rounds; from genus 8 (30 pi and more) a reach of 12 layers and half of the domain's faces
/// (the cone refinement puts more than half of them around the cone), kept only when the rim
/// comes clear within it, and one margin layer, the holes compared on uniform grids.
/// `fairing_free_cone`: the fit dropped the fairing constraints next to the cone
/// (ScanFitOptions::free_cone_faces_from_genus, FittedSurface::fit_unconstrained_faces > 0);
/// then the spline there no longer folds and the hole takes no reach (reach_layers 0), only
/// the caps, margin layer and vertex rounds: the reach would grow it to half of a small
/// domain's faces and a third of the surface's area (docs/design-notes.md, turbine).
[[nodiscard]] ConeHoleLimits cone_hole_limits(int genus, bool fairing_free_cone = false);

struct CapHolesOptions {
  /// The input had boundary loops of its own (then the domain's boundary rims are those loops;
  /// otherwise the only boundary is the puncture of a closed genus-0 input, always capped).
  bool open_input = false;
  bool fill_boundaries = false;  ///< Also cap the input's own boundary loops.
  /// By domain face, nonzero: a ghost face of the scan fit's boundary collar
  /// (ScanFitResult::collar_faces), fitted but beyond the surface's boundary: skipped, and the
  /// rims along it are boundary rims. Empty: no collar.
  std::vector<char> collar_faces;
  /// Growth limits of the cone hole (fit_surface: cone_hole_limits of the input's genus).
  ConeHoleLimits cone_hole;
  /// false: the rims are found (the cone hole grown past badly conditioned or folded faces,
  /// without the retries a flipping patch causes) and their faces skipped, but no patch is
  /// made and every rim stays open: the surface as a fit round is judged before the delivered
  /// round is capped (fit_surface).
  bool make_patches = true;
  /// A cheaper capping, to rank fit rounds before the one delivered is capped (fit_surface):
  /// the cone hole's patch is made once, on the hole the first find_rims gives (within its
  /// reach), without the comparison with the hole the caps give and without the vertex rounds
  /// (a patch that flips is still retried), and every patch on a uniform grid
  /// (FillOptions::corner_refinement 1). One patch per rim instead of 4-6 corner-refined ones.
  bool screening = false;
  /// When not null and set, cap_holes stops at its next check (FillOptions::cancel) and throws
  /// ricci::Cancelled, leaving `surface` partly capped.
  const std::atomic<bool>* cancel = nullptr;
};

/// Whether a capping with these limits retries the cone hole (vertex rounds, a reach), so that
/// CapHolesOptions::screening is cheaper than it; without retries it differs only by the grid.
[[nodiscard]] bool retries_cone_hole(const ConeHoleLimits& limits);

struct CapHolesReport {
  std::vector<std::string> failures;  ///< Rims whose fill was refused: "kind: reason".
  int boundary_rims = 0;   ///< Rims along the input's boundary loops (see FittedSurface).
  int fallback_fills = 0;  ///< Patches that are the positions-only fallback (not G1).
  double max_normal_jump_deg = 0.0;  ///< Largest seam normal jump over the patches.
  double max_position_gap = 0.0;     ///< Largest patch - spline gap over the domain diagonal.
};

/// Finds the rims of surface.spline over surface.domain and caps them: the cone hole (grown
/// past badly conditioned or folded faces; a patch that flips, seam > 90 degrees, is retried on
/// the hole grown by one and two more layers, the smallest seam kept), excluded-face holes, and
/// boundary rims as options say; a rim whose fill throws ricci::InvalidInputError stays open
/// and is reported. Then the spline's control points next to the rims move to meet the patches
/// (kept only when the largest seam drops). Sets surface.fills, open_rims, skipped_faces (the
/// faces outside the domain, the collar, and every rim's covered faces; an open rim's too when
/// there is no collar) and surface.spline.
/// With make_patches false only the rims and skipped_faces are set (open_rims holds every rim).
/// \pre surface.domain and surface.spline as fit_scan leaves them.
/// \throw ricci::SolverError when a patch's system cannot be solved; as find_rims;
///        ricci::Cancelled when options.cancel is set while it runs.
[[nodiscard]] CapHolesReport cap_holes(SplineSurface& surface, const CapHolesOptions& options);

}  // namespace spline

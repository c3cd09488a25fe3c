#pragma once
// The whole scan-to-surface job in one call: the scan fit (simplify, one-cone atlas, spline
// space, parameters, constrained fit, parameter correction), the patches capping the cone's
// hole (and, on request, the input's boundary loops), the surface moved to meet them, a
// watertight tessellation of spline and patches, and the figures that say whether it worked
// (distance to the scan, seam normal jumps, topology of the tessellation). `msp fit` is this
// call plus file output.
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "ricci/mesh/mesh.h"
#include "ricci/mesh/primitives.h"
#include "ricci/pipeline/one_cone_atlas.h"
#include "spline/fit/fit.h"
#include "spline/surface/adaptive_domain.h"
#include "spline/surface/spline_surface.h"
#include "spline/tessellate/dihedral.h"
#include "spline/tessellate/scan_distance.h"
#include "spline/tessellate/tessellate.h"

namespace spline {

/// The fairing order the fit takes at `degree` when none is given: 1 from degree 3, 0 below.
/// At degree 2, r = 1 is r = n - 1, which ties each face to its neighbours' polynomials so
/// closely that the fit leaves the input (models/genus2.off: a spike 7% of the diagonal out after
/// 27 rounds; r = 0: RMS 0.05%).
[[nodiscard]] constexpr int default_fairness(int degree) { return degree >= 3 ? 1 : 0; }

struct FitSurfaceOptions {
  int domain_faces = 2000;  ///< Target face count of the simplified domain mesh.
  int degree = 3;           ///< n of the DMS spline, 1..kMaxDmsDegree.
  /// r of the fairing constraints the fit obeys (-1: none); empty: default_fairness(degree).
  std::optional<int> fairness;
  /// `fairness`, or default_fairness(degree) when it is empty.
  [[nodiscard]] int fairness_order() const { return fairness.value_or(default_fairness(degree)); }
  /// Weight of the fit's thin-plate energy (FitOptions::smoothing, dimensionless).
  double smoothing = FitOptions{}.smoothing;
  /// Closed inputs: the domain's density follows the shape (adaptive_domain: splits where the
  /// scan departs from the domain or a part is thin), domain_faces its target, and the star of
  /// the automatically chosen cone split once (the cone goes where the domain is coarsest);
  /// false (default), or open inputs: one edge length (fit_scan's simplification).
  bool adaptive_domain = false;
  /// ScanFitOptions::tracked_parameters (genus >= 4: data placed through the flow's flips).
  bool tracked_parameters = false;
  /// The adaptive domain's sizing (its target_faces is replaced by domain_faces).
  AdaptiveDomainOptions sizing;
  /// Input-mesh vertex of the extraordinary point (an interior vertex), -1 to choose it by
  /// least area distortion. Ignored, but still checked, where there is no cone (open, tori).
  int singular_vertex = -1;
  bool fill_boundaries = false;  ///< Also cap the input's own boundary loops.
  /// Boundary loops of the input narrower than this fraction of its bounding-box diagonal (a
  /// scan's missing triangle) are capped before the fit (ricci::cap_small_holes); 0: none.
  double small_hole_diameter = 0.002;
  /// Tessellation samples per domain edge - 1; 0: chosen by domain size (default_density).
  int density = 0;
  /// The delivered tessellation is refined where adjacent triangles turn by more than
  /// density_refine_turn_deg, up to this many levels (refine_sharp_turns); 0: the uniform grid.
  int density_refine_levels = 3;
  double density_refine_turn_deg = 60.0;
  /// The run fails (ricci::SolverError, nothing delivered) when a point of the tessellated
  /// surface lies farther than this fraction of the input's bounding-box diagonal from the input
  /// (a spike or a sheet sticking out); 0 turns the guard off.
  double max_surface_deviation = 0.05;
  /// Refinement rounds: after a fit whose surface folds (normals turning by more than 90
  /// degrees across a tessellation edge) or, with a tolerance, misses input vertices by more
  /// than it, the domain is split around those places (new vertices on the input) and the fit
  /// run again with the same cone; the best round (fewest folds, then fewest vertices over the
  /// tolerance, then lowest RMS) is delivered. 0: one fit.
  int refinement_rounds = 1;
  /// Error goal as a fraction of the input's bounding-box diagonal (0: folds only).
  double tolerance = 0.0;
  /// RMS goal as a fraction of the input's bounding-box diagonal (0: none). When the first
  /// round's RMS over its data points (FitResult::rms_at_parameters) passes 0.8 times it, its
  /// RMS over the input's vertices (projection) is measured; when that exceeds it too and
  /// refinement_rounds > 0, the domain is split around the input vertices farther than 2.5 times
  /// the goal from the surface and the fit starts again on it with the same cone (the fold
  /// rounds and refinement follow on that round). When that round still exceeds the goal and
  /// the surface delivered from it folds, it is refined once more the same way, the rounds after
  /// it run again, and the new surface is delivered if it folds less (or as little with seams
  /// under 1 degree). A coarse input's data points are mostly on its flat facets, so rounding
  /// its corners does not count against the goal.
  double rms_goal = 0.0019;
  /// Fold rounds, after the refinement: while the surface folds, the domain faces within two
  /// rings of the folds (on open inputs: not within two of the boundary) are fitted again with
  /// at least fold_smoothing (FitOptions::smoothing's unit; three times more each further
  /// round) on the same domain and cone; a round is kept when it folds less (a sharp crease is
  /// rounded, not folded), and they stop after two rounds in a row that do not, or at once
  /// after a round that leaves as many folds at the same RMS (within 1e-4 of it). On closed
  /// inputs a series that leaves folds is run again from its start with the raised smoothing
  /// tapered over three more rings (fold_smoothing.h), and the better series is kept. Without
  /// a tolerance they run first, on the first fit (open inputs: when no fold lies within two
  /// rings of the boundary): when that leaves no fold (capped too) the refinement is skipped,
  /// otherwise the refinement and its fold rounds follow and the better of the two is
  /// delivered. 0: none.
  int fold_rounds = 6;
  double fold_smoothing = 1e-2;
  /// The fold rounds stop at the first whose RMS (projection) exceeds both this factor times
  /// the RMS before them (>= 1) and fold_rms_goal: folds are traded for error only this far.
  double fold_rms_growth = 1.25;
  /// The factor instead of fold_rms_growth while every fold left lies within two median domain
  /// edges of an edge where the input folds itself (mesh_fold_points, fold_smoothing.h): a
  /// jagged scan, whose folds the surface rounds rather than follows.
  double crease_fold_rms_growth = 2.0;
  /// Closed inputs: RMS (projection, fraction of the input's bounding-box diagonal) the fold
  /// rounds may always reach, below the 0.2% asked of smooth scans; 0: the growth factor alone.
  double fold_rms_goal = 0.0019;
  /// The delivery rule between folds and RMS (issue 15's acceptance: no fold, RMS below 0.2% of
  /// the diagonal on a smooth scan): a fold round that leaves no fold but is refused by the
  /// limits above is kept aside when its RMS (projection) is within this fraction of the
  /// diagonal, and when the round otherwise delivered folds (capped), the fold-free one with the
  /// lowest RMS is capped and delivered instead if it still does not fold and stays within it.
  /// 0: off (a folded round may be delivered whatever the fold-free ones' RMS).
  double fold_free_rms = 0.002;
  /// Measures of the delivered surface against the input (coverage tolerance, threads).
  ScanDistanceOptions measure;
  /// Denser domain around the cone (levels 0: off; ricci/singularity/one_cone.h).
  ricci::ConeRefinementOptions cone_refinement = ScanFitOptions{}.atlas.cone_refinement;
  /// Optional: called with a stage name when the stage starts (the names of `seconds`).
  std::function<void(const std::string& stage)> progress;
};

/// Checks the ranges of the options: domain_faces >= 1, degree in [1, kMaxDmsDegree], fairness
/// -1 or in [0, degree - 1], smoothing in [0, 1e6), density in [0, 64],
/// density_refine_levels in [0, 6], density_refine_turn_deg in (0, 180), cone_refinement.levels
/// in [0, 4], refinement_rounds in [0, 8], tolerance in [0, 1), max_surface_deviation in
/// [0, 10], fold_rounds in [0, 8], fold_smoothing in (0, 1e6), fold_rms_growth >= 1,
/// crease_fold_rms_growth >= 1, fold_rms_goal, fold_free_rms and rms_goal in [0, 1),
/// small_hole_diameter in [0, 1). `name`
/// spells a field (given as "domain_faces", "cone_refinement", ...) the way the caller's user
/// knows it, e.g. msp fit's
/// "--domain-faces" (default: the field's own name).
/// \throw ricci::InvalidInputError naming the first option out of range and its range.
void check_options(const FitSurfaceOptions& options,
                   const std::function<std::string(const std::string& field)>& name = {});

/// One fit round of fit_surface (the first, then each refinement or fold round), measured
/// before the holes are capped (the patches and the vertices over them are not in it).
struct RefinementRound {
  int domain_faces = 0, control_points = 0;
  int folds = 0;  ///< Tessellation edges over 90 degrees.
  double projection_rms = 0.0, projection_max = 0.0;  ///< As FittedSurface's.
  int vertices_over_tolerance = -1;                   ///< -1 without a tolerance.
  /// A refinement round that failed (its atlas or fit threw): the error, the other figures
  /// zero; the rounds before it are delivered. Empty otherwise.
  std::string error;
};

/// Wall-clock or CPU seconds by stage, in the order run, then "total".
using StageSeconds = std::vector<std::pair<std::string, double>>;

struct FittedSurface {
  /// The delivered surface: domain mesh, spline (moved to meet the patches), the patches,
  /// the rims left open and the faces the patches cover.
  SplineSurface surface;
  ricci::SurfaceTopology input;  ///< Of the input mesh with its small holes capped.
  /// The input's boundary loops capped as small holes and the largest one's diameter (fraction
  /// of the diagonal); they are left out of delivered's boundary comparison.
  int capped_holes = 0;
  double capped_hole_diameter = 0.0;
  /// The one-cone atlas the spline is built on (cut loops, charts, flow, cone refinement);
  /// atlas.problem.mesh equals surface.domain.
  ricci::OneConeAtlasResult atlas;
  /// Closed genus 0 with the automatic singularity: where the puncture went and why
  /// (ScanFitResult::puncture); vertex -1 otherwise.
  PunctureChoice puncture;
  /// The adaptive domain (0 and empty without): faces of its uniform base, faces split by level.
  int domain_base_faces = 0;
  std::vector<int> domain_split_faces;
  double fit_constraint_residual = 0.0;  ///< Largest |C c| of the constrained fit.
  /// Domain faces fitted free of the fairing constraints next to the cone
  /// (ScanFitOptions::free_cone_faces_from_genus).
  int fit_unconstrained_faces = 0;
  /// Open inputs: by domain face, the ghost faces of the boundary collar (ScanFitResult); why
  /// the collar was dropped, if it was; what follow_boundary did to the domain's boundary.
  std::vector<char> collar_faces;
  std::string collar_refused;
  ricci::BoundaryFollowResult boundary_follow;
  /// The surface fitted with its boundary pulled onto the scan's (ScanFitOptions::boundary_curve)
  /// folded, and the fit without that pull, on the same domain, folded less and was kept.
  bool boundary_curve_dropped = false;
  /// tessellate_surface(surface) at the chosen density: spline and patches, welded.
  Tessellation tessellation;
  WatertightReport topology;  ///< Of the tessellation (position indices).
  /// Of the tessellation rounded to float and welded by value, as a file holds it (a surface
  /// that collapses somewhere shows degenerate triangles here, not in `topology`).
  WatertightReport float_topology;
  /// Angles between adjacent triangles of the tessellation (folds show as > 90 degrees).
  DihedralReport surface_dihedral;
  /// Manifold (as computed and float-welded) of the input's genus, with one boundary loop per
  /// rim left open on purpose (a failed fill leaves one more: not watertight).
  bool watertight = false;
  std::vector<std::string> fill_failures;  ///< Rims whose fill was refused, with the reason.
  /// Rims along the input's boundary loops: with fill_boundaries fewer than its loops where
  /// loops a ring or two apart merged into one hole (spline/fill/rims.h); without, one per loop.
  int boundary_rims = 0;
  int fallback_fills = 0;           ///< Patches that are the positions-only fallback (not G1).
  /// The delivered surface (the tessellation rounded to float and welded, as a file holds it)
  /// measured against the input by global closest-point queries both ways: every input vertex
  /// to the surface, the surface's vertices and triangle centroids to the input, coverage and
  /// the distance between the two boundaries (spline/tessellate/scan_distance.h).
  ScanDistanceReport delivered;
  /// delivered.fit_rms / fit_max / scan_points: every input vertex to the delivered surface.
  double fit_rms = 0.0, fit_max = 0.0;
  int fit_points = 0;
  /// The exact spline's distances: input vertices whose parameter lies on a tessellated face,
  /// projected onto the spline from that parameter; the others (the cone's star, faces a patch
  /// covers) measured against the nearest patch; a vertex near neither is left out (counted
  /// in fit_points - projection_points).
  double projection_rms = 0.0, projection_max = 0.0;
  int projection_points = 0;
  int fit_points_on_fills = 0;          ///< Of the projected points, measured against a patch.
  double bbox_diagonal = 0.0;           ///< Of the input.
  double edge_normal_jump_deg = 0.0;    ///< Across domain edges (the spline's own seams).
  double fill_normal_jump_deg = 0.0;    ///< Across the patches' rims.
  double fill_position_gap = 0.0;       ///< Largest gap patch - spline over the domain diagonal.
  /// Every round run (the first, then the refinements); the surface is the best one's.
  std::vector<RefinementRound> refinement;
  StageSeconds seconds;                 ///< Wall clock by stage (a stage run again adds up).
  /// CPU seconds of the process (all threads) by stage: on a shared machine the wall clock
  /// includes waiting for a core, this does not.
  StageSeconds cpu_seconds;
};

/// "" when the delivered tessellation (`topology`, and `float_topology` as a file holds it) is
/// a manifold with the input's Euler characteristic and one boundary loop per rim left open on
/// purpose; otherwise one line saying how it differs, e.g. a closed surface of another genus
/// (a patch capped a handle: a hole that held one was filled by a disk). fit_surface does not
/// throw on this: the caller decides (msp fit writes its outputs and exits non-zero).
[[nodiscard]] std::string topology_mismatch(const FittedSurface& fitted);

/// Where the delivered surface folds (fold_places, tessellate/dihedral.h): on the patches, on the
/// spline next to the cone, elsewhere. "Next to the cone" is within kNearConeHoleRadii times the
/// cone hole's radius (the farthest 3D distance from the cone to a corner of the faces its patch
/// covers) of the cone, where the one-cone metric's scale changes fastest; 0 (every spline
/// fold elsewhere) without a cone or a cone patch.
inline constexpr double kNearConeHoleRadii = 3.0;
struct SurfaceFoldPlaces {
  FoldPlaces places;
  double near_cone_radius = 0.0;  ///< The radius used, absolute.
};
[[nodiscard]] SurfaceFoldPlaces surface_fold_places(const FittedSurface& fitted);

/// Smallest FitSurfaceOptions::domain_faces for a surface of this genus: the domain must hold
/// the cone's star, the cut graph's 2g loops and a vertex chart around each.
[[nodiscard]] int minimum_domain_faces(int genus);

/// Fits the surface to `dense` (its vertices and face centroids; its small holes capped first)
/// and caps the surface's holes: the cone
/// hole always (grown, and retried on a bigger hole where its patch flips), excluded-face holes
/// always, boundary loops with fill_boundaries (a closed genus-0 input's puncture always).
/// Every round (the first, each refinement or fold round) is judged with its holes found but
/// not capped; the delivered round alone is capped. Stages: "domain" (the adaptive domain),
/// "singularity" (with a given vertex), fit_scan's, "rims", "tessellate", "measure", then
/// "refine" and the same again per refinement or fold round, then "fill", "tessellate" and
/// "measure" of the delivered round (a stage run again adds to its first entry).
/// \pre `dense` is a connected oriented 2-manifold triangle mesh.
/// \throw ricci::InvalidInputError for options out of range (check_options), a singular vertex
///        out of range or on the boundary, or fewer domain faces (asked for, or in the mesh)
///        than minimum_domain_faces;
///        ricci::SolverError when the surface strays farther than max_surface_deviation from the
///        input; as fit_scan otherwise.
[[nodiscard]] FittedSurface fit_surface(const ricci::Mesh& dense,
                                        const FitSurfaceOptions& options = {});

}  // namespace spline

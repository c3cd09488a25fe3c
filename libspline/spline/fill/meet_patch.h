#pragma once
// The surface next to the filled rims moved to meet the patches (the second half of a G1 fill).
//
// fill_rim fits the patch to the surface; what limits the seam after that is the surface: next
// to the rim's vertices its normal turns by 1.5-8 degrees within 1/100 of a rim edge (the DMS
// pieces of the faces around a vertex join within its knot cloud), faster than a patch of a few
// triangles per rim edge can turn. So the surface's control points near the rims are moved a
// little, all rims in one least-squares problem:
//   rows n_P . D_d S(c + dc) = 0 for the chart's two axes d (S's tangent plane contains the
//     patch's normal n_P: the surface meets the fixed patch tangentially), scaled by 1 / |D_d S|
//     (so a row is the sine of the angle it removes), at fill_detail::rim_edge_parameters
//     (samples_per_edge per rim edge, graded towards its vertices: a function whose support
//     meets the rim only within a vertex's knot cloud, between uniform samples, would otherwise
//     move unseen and pleat the surface there);
//   rows S(c + dc) = S(c) at the same samples (the rim, where patch and surface are welded,
//     stays in place);
//   change_weight * |dc| / h for every moved control point (h: the rims' mean 3D edge length):
//     the smallest change;
//   then (MeetPatchOptions::peak_rounds) the same rows again plus rows at measure_seam's samples
//     of the moved surface, where it peaks between the first rows.
// Unknowns: the control points of the functions that are non-zero at some sample (their
// supports reach at most a ring beyond the rim; those of covered faces only change what the
// patch hides). The spline stays C^2 (any control points give a smooth DMS spline); its fit to
// the data changes only next to the rims.
#include <Eigen/Core>
#include <vector>

#include "spline/fill/hole_fill.h"
#include "spline/manifold/manifold_space.h"

namespace spline {

struct MeetPatchOptions {
  int samples_per_edge = 200;  ///< tangency and position samples per rim edge
  double position_weight = 1.0;  ///< of the rows keeping S on the rim (per unit of h)
  /// Of the smallest-change rows; small, so that the tangency rows win, but non-zero so that
  /// functions the rows do not determine stay put.
  double change_weight = 0.1;
  /// Solves again with rows added where the moved surface's seam peaks between the rows
  /// (measure_seam's refined samples), this many times; the move with the smallest seam is
  /// returned. The rows alone trade their mean for peaks between them: generated genus 8's
  /// cone patch (82 rim edges) 6.5 degrees before the move, 17.1 after it, 2.7 after one round.
  int peak_rounds = 1;
};

struct MeetPatchResult {
  Eigen::MatrixX3d control_points;  ///< the spline's, with the rims' neighbourhood moved
  int moved_functions = 0;
  double max_change = 0.0;  ///< max |dc| / h
  /// With MeetPatchOptions::peak_rounds > 0: measure_seam (default samples) of every fill on the
  /// returned control points, which the rounds were ranked by; empty otherwise.
  std::vector<SeamReport> seams;
};

/// \pre every fill was made by fill_rim on `spline`'s space and mesh.
/// \throw ricci::InvalidInputError on bad options; ricci::SolverError when the solve fails.
[[nodiscard]] MeetPatchResult meet_patches(const ManifoldSpline& spline,
                                           const std::vector<HoleFill>& fills,
                                           const MeetPatchOptions& options = {});

}  // namespace spline

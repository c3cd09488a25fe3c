#pragma once
// Building blocks of the atlas: developing a set of faces into one planar chart, and checking
// that a face's neighbourhood lies in a chart as one glued piece.
#include <vector>

#include <Eigen/Core>

#include "ricci/atlas/atlas.h"

namespace ricci::detail {

/// Faces within two rings of `vertices` (faces touching a vertex that shares a face with one of
/// them), restricted to faces with in_domain set. Unordered, unique.
[[nodiscard]] std::vector<int> two_ring_faces(const Mesh& mesh, const std::vector<int>& vertices,
                                              const std::vector<char>& in_domain);

/// Develops `region` (original faces) into the plane breadth-first from `seed_face`, whose corners
/// are put at `seed_positions` (row k = corner k), by directions (layout_e2.h,
/// develop_directions) in long double. Each face is placed once; copies of a vertex
/// reached along different routes are glued when they land within `glue_distance` of each
/// other across a shared edge. \pre seed_face is in region.
[[nodiscard]] Chart develop_chart(const Mesh& mesh, const LongLengths& lengths,
                                  const std::vector<int>& region, int seed_face,
                                  const Eigen::Matrix<double, 3, 2>& seed_positions,
                                  double glue_distance);

/// Domain faces sharing a vertex with `face` (including it).
[[nodiscard]] std::vector<int> face_neighbourhood(const Mesh& mesh, int face,
                                                  const std::vector<char>& in_domain);

/// True when every face of `neighbourhood` is in `chart` and each original vertex has a single
/// chart copy across them (the neighbourhood is one glued planar piece).
[[nodiscard]] bool holds_as_one_piece(const Mesh& mesh, const Chart& chart,
                                      const std::vector<int>& neighbourhood);

/// Whether `chart` (row `row`) places `face` faithfully: counter-clockwise, with edges of their
/// metric `lengths` to a relative 1e-9. Near a cone of 2 pi (2g - 1) at genus 8 and beyond the
/// flat metric shrinks faces far below the rounding of a chart's coordinates, which then flips
/// or collapses them; the spline needs every face's neighbourhood in a chart placing it
/// faithfully, because its knot clouds move between charts by rigid motions (two charts placing
/// a face differently by d, relative, give two surfaces d apart).
[[nodiscard]] bool places_faithfully(const Mesh& mesh, const Eigen::VectorXd& lengths,
                                     const Chart& chart, int row, int face);

/// Fills atlas.transitions, atlas.face_transitions and atlas.max_transition_residual: one
/// rigid motion per connected piece of every pair of overlapping charts (Kabsch fit), fitted and
/// measured on the piece's faces that both charts place faithfully; a piece with none is fitted
/// on all its faces and counted in atlas.unresolved_transition_pieces instead.
void compute_transitions(const Mesh& mesh, const Eigen::VectorXd& lengths, AffineAtlas& atlas);

/// Fills atlas.side_pairings and atlas.max_side_pairing_residual from the central chart.
void compute_side_pairings(const Mesh& mesh, AffineAtlas& atlas);

}  // namespace ricci::detail

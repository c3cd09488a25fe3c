#pragma once
// Geometry behind the atlas picture: the outline of the fundamental domain in the central
// chart, the cut sides with their names, and the deck transformations that place copies of the
// domain around it (a patch of the universal cover).
#include <array>
#include <string>
#include <vector>

#include <ricci/atlas/atlas.h>
#include <Eigen/Core>

namespace msp {

/// The boundary of the central chart as a closed polygon, counter-clockwise: sliced-mesh vertex
/// indices and their chart positions (rows).
struct DomainOutline {
  std::vector<int> vertices;
  Eigen::MatrixX2d points;
  double signed_area = 0.0;  ///< Of the outline polygon (> 0).
};

/// \throw ricci::TopologyError if the sliced mesh has no boundary (never for a valid atlas).
[[nodiscard]] DomainOutline domain_outline(const ricci::AffineAtlas& atlas);

/// One side of a side pairing drawn in the central chart: a polyline walked along the arc.
struct CutSide {
  int pairing = -1;  ///< Index into AffineAtlas::side_pairings.
  bool left = true;  ///< Left side (faces of the arc's halfedges) or right side.
  Eigen::MatrixX2d
      points;  ///< Arc vertices in order (from of the first halfedge ... to of the last).
};

/// Both sides of every side pairing, in pairing order (left, right, left, right, ...).
[[nodiscard]] std::vector<CutSide> cut_sides(const ricci::Mesh& mesh,
                                             const ricci::AffineAtlas& atlas);

/// Colour of loop `loop` in the pictures (sRGB, 8 bits per channel); grey for -1 (tree arcs).
[[nodiscard]] std::array<int, 3> loop_colour_rgb(int loop);
/// The same as "#rrggbb".
[[nodiscard]] std::string loop_colour_hex(int loop);

/// Names of the loops: a1 b1 a2 b2 ... following polygon.canonical_order when the word is
/// canonical, else c1 c2 ... by loop index.
[[nodiscard]] std::vector<std::string> loop_names(const ricci::AffineAtlas& atlas);

/// Deck transformations for the copies of the domain: all products of 1..depth side-pairing
/// motions and their inverses, without the identity and without repeats (two motions are the
/// same when angles differ by < 1e-9 and translations by < tolerance * domain diameter).
/// Depth 1 is the first ring of copies (one across each side).
[[nodiscard]] std::vector<ricci::RigidMotion2> cover_motions(const ricci::AffineAtlas& atlas,
                                                             int depth, double tolerance = 1e-7);

/// Winding number of the closed polygon `polygon` (rows) around `point`: 1 inside a
/// counter-clockwise simple polygon, 0 outside, k where an immersed disk covers the point k times.
[[nodiscard]] int winding_number(const Eigen::MatrixX2d& polygon, const Eigen::Vector2d& point);

/// `points` (rows) moved by `motion`.
[[nodiscard]] Eigen::MatrixX2d transformed(const Eigen::MatrixX2d& points,
                                           const ricci::RigidMotion2& motion);

}  // namespace msp

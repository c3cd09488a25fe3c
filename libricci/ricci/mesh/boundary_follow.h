#pragma once
// A simplified mesh whose boundary follows the dense mesh's: boundary edges of the simplified
// mesh split where the dense boundary strays from them, the new vertex put on the dense boundary.
// Simplification shortens a boundary loop to chords of the domain's edge length; a small hole or
// a notch of the scan then lies a few percent of the diagonal from the chords.
#include "ricci/mesh/boundary_band.h"
#include "ricci/mesh/mesh.h"

namespace ricci {

struct BoundaryFollowOptions {
  /// Largest distance wanted between the two boundaries (both ways), as a fraction of the dense
  /// mesh's bounding-box diagonal.
  double tolerance = 0.002;
  int max_rounds = 6;  ///< Rounds of splits (each splits every edge still too far, once).
  /// Spread boundary vertices that bunch along the dense boundary (see follow_boundary).
  bool spread = true;
  /// Loops still farther than band.rebuild_above from the dense boundary after the splits have
  /// their band rebuilt from the dense loop's vertices (boundary_band.h).
  BoundaryBandOptions band{};
};

struct BoundaryFollowResult {
  int splits = 0;  ///< Boundary edges split (one vertex and one face each).
  int rounds = 0;
  int spread = 0;  ///< Moves of bunched boundary vertices along the dense boundary.
  int loops_rebuilt = 0;  ///< Loops whose band was rebuilt (rebuild_boundary_bands).
  /// Hausdorff distance between the boundary curves (vertices and edge midpoints sampled)
  /// before and after, as fractions of the dense mesh's diagonal; 0 without boundary.
  double distance_before = 0.0, distance_after = 0.0;
};

/// Splits boundary edges of `coarse` (in place) until every dense boundary vertex is within the
/// tolerance of the coarse boundary and every coarse boundary edge's midpoint within it of the
/// dense boundary, or max_rounds. A split edge's new vertex goes to the dense boundary point
/// farthest from the edge among those nearest to it (or the dense boundary point nearest to the
/// midpoint), moved back towards the midpoint as far as needed for its two triangles to keep
/// the split face's orientation; an edge that cannot be split so is left. With `spread`, each
/// round first moves a coarse boundary vertex closer (in arc length along the dense loop it
/// follows) than a third of its loop's mean spacing to a neighbour to the middle of its two
/// neighbours: projected onto a zigzag boundary, several vertices land in one V-notch and the
/// teeth between them are left out; the result with the spread is kept only when its boundary
/// ends no farther from the dense one than without (a small hole's few corners). Then the loops
/// still farther than band.rebuild_above have their band rebuilt (rebuild_boundary_bands: the
/// faces along them replaced by a strip to the dense loop's own vertices; vertex indices change).
/// The topology does not change. Nothing happens when either mesh has no boundary.
/// \throw InvalidInputError for a tolerance <= 0 or max_rounds < 0; as rebuild_boundary_bands.
BoundaryFollowResult follow_boundary(Mesh& coarse, const Mesh& dense,
                                     const BoundaryFollowOptions& options = {});

}  // namespace ricci

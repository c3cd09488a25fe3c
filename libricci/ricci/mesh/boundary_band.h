#pragma once
// Rebuilding the band along a boundary loop of a simplified mesh from the dense mesh's own
// boundary vertices: where moving and splitting the simplified boundary cannot follow the dense
// one (a zigzag of one-triangle teeth narrower than a simplified edge), the faces touching the
// loop are replaced by a strip stitched between the ring inside them and the dense loop.
#include "ricci/mesh/mesh.h"

namespace ricci {

struct BoundaryBandOptions {
  /// A loop of the coarse mesh farther than this from the dense loop it follows (Hausdorff
  /// distance between the two curves, as a fraction of the dense mesh's bounding-box diagonal)
  /// is rebuilt; 0 or less: none.
  double rebuild_above = 0.004;
  /// The dense loop's vertices are thinned (Douglas-Peucker) to this distance from it, as a
  /// fraction of the diagonal.
  double tolerance = 0.002;
  /// Flattest triangle the strip may hold (twice its area over its longest edge squared; an
  /// equilateral triangle has 0.87).
  double min_shape = 0.02;
};

struct BoundaryBandResult {
  int loops_rebuilt = 0;
  int faces_removed = 0, faces_added = 0;
};

/// For each boundary loop of `coarse` farther than options.rebuild_above from the boundary loop
/// of `dense` it follows: the faces with a corner on the loop are removed and the ring of
/// vertices inside them is stitched to the dense loop's vertices (thinned to options.tolerance)
/// by a strip of triangles, chosen by dynamic programming for the shortest total rung length
/// among strips whose triangles face like the dense surface at their dense corners and are no
/// flatter than options.min_shape. A loop is left as it was when the removed faces are not a
/// strip (the ring inside is not one simple loop apart from the other boundaries) or when no
/// such strip exists; nothing changes when the rebuilt mesh is not a manifold. The rebuilt mesh
/// keeps the genus, the boundary loop count and the orientation; vertex indices are compacted.
/// \pre both meshes are oriented 2-manifolds, `coarse` a simplification of `dense` (the same
///      orientation).
/// \throw InvalidInputError for a tolerance <= 0 or min_shape outside [0, 1).
BoundaryBandResult rebuild_boundary_bands(Mesh& coarse, const Mesh& dense,
                                          const BoundaryBandOptions& options = {});

}  // namespace ricci

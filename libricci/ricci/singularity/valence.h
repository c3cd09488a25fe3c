#pragma once
// Valence modification around a cone vertex (manifold-splines paper, section 4, step 2).
// A cone of curvature K at p is only reachable by a circle-packing metric when p has enough
// neighbours; splitting an edge of p's link at its midpoint adds one neighbour and leaves the
// surface geometry unchanged (the new vertex lies on a straight edge, so it is flat).
#include <vector>

#include "ricci/mesh/mesh.h"

namespace ricci {

struct ValenceOptions {
  /// Target curvature at the cone vertex (radians); 2*pi*chi for the one-cone metric.
  double cone_curvature = 0.0;
  /// Minimum valence asked of the original vertices within `rings` rings of the cone.
  int ring_valence = 6;
  /// How many rings around the cone the `ring_valence` rule covers (the paper uses 3).
  int rings = 3;
  /// Extra neighbours for the cone beyond the paper's bound 4 - 2K/pi.
  int cone_valence_margin = 0;
  /// Safety cap on the number of edge splits.
  int max_splits = 100000;
};

struct ValenceResult {
  Mesh mesh;                  ///< The modified mesh; original vertices keep their indices.
  VertexHandle cone;          ///< The cone vertex in `mesh` (same index as in the input).
  int cone_valence_before = 0;
  int cone_valence_after = 0;
  int required_cone_valence = 0;
  int splits = 0;             ///< Number of vertices added (one per edge split).
  int ring_vertices_below = 0;  ///< Original ring vertices still below ring_valence (boundary).
};

/// The paper's bound on the cone valence: the smallest integer >= 4 - 2K/pi.
[[nodiscard]] int required_cone_valence(double cone_curvature);

/// Splits edges of the cone's link, then of deficient ring vertices' links, at their midpoints.
/// Splits always take the longest admissible link edge, which keeps the new triangles fat.
/// \pre `cone` is an interior vertex of a triangle mesh.
/// \throw InvalidInputError if the cone is a boundary vertex or out of range.
[[nodiscard]] ValenceResult modify_valence(const Mesh& mesh, VertexHandle cone,
                                           const ValenceOptions& options = {});

/// Vertices within `rings` rings of `center` (excluding it), by breadth-first search.
[[nodiscard]] std::vector<VertexHandle> ring_neighbourhood(const Mesh& mesh, VertexHandle center,
                                                           int rings);

}  // namespace ricci

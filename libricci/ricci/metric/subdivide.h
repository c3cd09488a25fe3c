#pragma once
// Midpoint (1-to-4) subdivision: the benchmark's way to make large meshes from real ones.
#include <vector>

#include "ricci/mesh/mesh.h"

namespace ricci {

/// Splits every triangle into four by its edge midpoints. Vertex i of the input keeps index i;
/// the midpoint of edge e gets index #V + e. Topology (genus, boundaries) is unchanged.
/// \throw InvalidInputError if a face is not a triangle.
[[nodiscard]] Mesh subdivide_midpoint(const Mesh& mesh);

/// Red-green midpoint refinement of the faces flagged in `refine` (by face index): they split
/// 1-to-4; a neighbour with two split edges is split 1-to-4 too (repeated until stable), one with
/// a single split edge is bisected from its opposite corner, so no T-junction remains. Midpoints
/// lie on the straight edges (the surface is unchanged). Vertex i keeps index i; midpoints are
/// appended. Returns the mesh unchanged (a copy) when nothing is flagged.
/// \throw InvalidInputError if a face is not a triangle or `refine` has the wrong size.
[[nodiscard]] Mesh subdivide_midpoint_locally(const Mesh& mesh, const std::vector<char>& refine);

}  // namespace ricci

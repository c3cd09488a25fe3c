#pragma once
// Garland-Heckbert quadric edge collapse on the library's OpenMesh mesh, without CGAL: the
// first stage of simplify_mesh (simplify.h).
//
// Why not CGAL's edge_collapse: after every collapse it recomputes the cost and placement of the
// whole 2-ring of edges (its policies may depend on the link); plane quadrics depend only on the
// two end vertices, so only the edges at the new vertex change, which makes the decimation of a
// large scan several times cheaper.
//
// Rules (those of CGAL's GarlandHeckbert_plane_policies + Bounded_normal_change_placement):
// vertex quadrics are sums of the unit planes of the incident faces, plus planes through
// boundary edges perpendicular to their face (weight kBoundaryWeight, so open rims keep their
// shape); an edge's cost is the quadric error at the optimal point of Q_a + Q_b (the best of the
// ends and the midpoint when that 3x3 system is near singular). A collapse is refused when it
// breaks the link condition (OpenMesh's is_collapse_ok: the topology cannot change) or turns
// the normal of a remaining face by 90 degrees or more (no fold-overs).
#include "ricci/mesh/mesh.h"

namespace ricci {

struct QuadricDecimateOptions {
  /// Slabs across the longest axis of the bounding box decimated at once, each with one queue
  /// and the vertices at the cuts locked, down to twice the target in all, before one queue
  /// over the whole mesh takes it to the target. 0: two for inputs of 400,000 faces or more,
  /// else one (one queue all the way).
  int regions = 0;
  /// Threads for the regions (0 = hardware concurrency); the result does not depend on it.
  int threads = 0;
};

/// Collapses edges of `mesh` in order of quadric cost (in each region, then over the whole
/// mesh) until it has at most `target_faces` faces or no collapse is allowed; returns the face
/// count reached. Garbage is collected.
int quadric_decimate(Mesh& mesh, int target_faces, const QuadricDecimateOptions& options = {});

}  // namespace ricci

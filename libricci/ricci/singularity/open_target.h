#pragma once
// A boundary curvature target for open surfaces that the flow can reach: the boundary geodesic
// curvature of the flat metric whose conformal factor vanishes on the boundary (the Dirichlet
// problem, as boundary-first flattening's minimal-distortion boundary condition), predicted to
// first order. Spreading 2*pi*chi by length bends the loops of scans with many holes so far from
// their shape that no fixed-connectivity metric reaches it (lion, stanford-bunny); this target
// keeps the boundary's lengths, so the flow only has to correct second-order terms.
#include "ricci/flow/targets.h"
#include "ricci/mesh/mesh.h"

namespace ricci {

/// Interior vertices get 0; boundary vertex b gets K_b + (L_BI du_I)_b, where K is the mesh's
/// curvature, L the cotangent Laplacian (dK/du for vertex scaling l_ij = e^{(u_i + u_j)/2} l_ij)
/// and du_I solves L_II du_I = -K_I (flat interior, du = 0 on the boundary). The targets sum to
/// 2*pi*chi exactly (L's columns sum to zero).
/// \throw InvalidInputError for a closed mesh or degenerate faces; SolverError when L_II cannot be
///        factorised (a mesh without interior vertices gets the mesh's own boundary curvature).
[[nodiscard]] Targets harmonic_boundary_target(const Mesh& mesh);

}  // namespace ricci

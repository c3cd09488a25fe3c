#pragma once
// Distances along rays to a mesh: the local thickness of thin parts (the shape diameter) seen
// from the surface itself. Bodies use CGAL (ray_cast_cgal.cpp).
#include <Eigen/Core>

#include "ricci/mesh/mesh.h"

namespace ricci {

/// Thickness of `mesh` at every face: the distance from the face's centroid, along its normal
/// and against it, to the first other face hit, the smaller of the two (so the orientation of
/// the mesh does not matter); +infinity where neither ray hits. On a thin plate this is the
/// distance to the opposite sheet; between two nearby parts the gap between them.
/// \pre a triangle mesh (open or closed). \throw nothing for degenerate faces (their entry is
/// +infinity).
[[nodiscard]] Eigen::VectorXd face_thickness(const Mesh& mesh);

}  // namespace ricci

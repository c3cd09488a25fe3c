#pragma once
// Internal to the procedural meshes (primitives*.cpp, generate*.cpp): not a public header.
#include <array>
#include <vector>

#include <Eigen/Core>

#include "ricci/mesh/mesh.h"

namespace ricci::detail {

/// Builds a mesh from points and counter-clockwise triangles.
/// \throw TopologyError naming `what` and the face if OpenMesh refuses a face (non-manifold).
Mesh mesh_from_arrays(const std::vector<Eigen::Vector3d>& points,
                      const std::vector<std::array<int, 3>>& triangles, const char* what);

}  // namespace ricci::detail

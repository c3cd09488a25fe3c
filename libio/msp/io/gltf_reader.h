#pragma once
// Reading a triangle mesh back from a .glb, the way a viewer sees it: what the checks of the
// delivered surface (tests, msp-bench check-glb) measure, independently of how it was written.
#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace msp::gltf {

struct TriangleSurface {
  /// Positions as stored (float32, widened), welded by value: render vertices that a seam of
  /// texture coordinates splits are one position again.
  Eigen::MatrixX3d positions;
  std::vector<std::array<int, 3>> triangles;  ///< Position indices.
  int render_vertices = 0;                    ///< Vertices as stored, before welding.
};

/// The triangles of every primitive (mode TRIANGLES) of the meshes called `mesh_name` in the
/// .glb at `path` (all triangle meshes when `mesh_name` is empty), with their nodes' transforms
/// ignored (msp writes identity nodes).
/// \throw ricci::IOError when the file cannot be read or is not a valid glTF binary, or holds no
///        such mesh; accessors of the wrong type or out of range are refused the same way.
[[nodiscard]] TriangleSurface read_glb_triangles(const std::string& path,
                                                 const std::string& mesh_name = "surface");

}  // namespace msp::gltf

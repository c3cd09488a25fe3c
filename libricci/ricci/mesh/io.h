#pragma once
// Reading and writing meshes. Readers refuse malformed files with an IOError naming the file and
// the line (or face/vertex index) at fault.
#include <string>
#include <string_view>

#include "ricci/mesh/mesh.h"

namespace ricci {

/// Reads an OBJ, OFF, PLY or STL file (optionally .gz) into a triangle mesh: read_soup() then
/// build_mesh() (polygons triangulated, unreferenced vertices dropped, faces oriented).
/// \throw IOError on unreadable or malformed files; TopologyError when the faces are not a
///        single-component orientable 2-manifold; InvalidInputError on NaN/inf coordinates or
///        degenerate faces. Messages start with the file name.
[[nodiscard]] Mesh read_mesh(const std::string& path);

/// A mesh and the colours its file gives its vertices.
struct ColouredMesh {
  Mesh mesh;
  /// #V by 3: RGB in [0, 1] by mesh vertex; 0 rows when the file has no vertex colours (OFF
  /// keywords with a C: "r g b [a]" after the coordinates and the normal, 0-255 or 0-1; PLY
  /// red, green, blue: integer types over 255).
  Eigen::MatrixX3d colours;
};

/// read_mesh() keeping the vertex colours (see ColouredMesh). \throw as read_mesh(), and
/// IOError on a colour that is not finite or lies outside 0-1 (0-255 for integer colours).
[[nodiscard]] ColouredMesh read_mesh_with_colours(const std::string& path);

/// Writes OBJ, OFF or PLY (ascii), chosen by the extension, with every coordinate in the
/// shortest decimal form that reads back to the same double. The file appears atomically
/// (written to a temporary next to it, then renamed). \throw IOError.
void write_mesh(const Mesh& mesh, const std::string& path);

/// Writes `bytes` to `path` atomically: to a temporary next to it, then renamed into place, so a
/// reader never sees a half-written file and a failure leaves nothing behind. \throw IOError.
void write_file_atomically(const std::string& path, std::string_view bytes);

}  // namespace ricci

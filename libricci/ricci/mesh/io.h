#pragma once
// Reading and writing meshes. Readers refuse malformed files with an IOError naming the file and
// the line (or face/vertex index) at fault.
#include <string>

#include "ricci/mesh/mesh.h"

namespace ricci {

/// Reads an OBJ, OFF, PLY or STL file (optionally .gz) into a triangle mesh.
/// \throw IOError on unreadable or malformed files; TopologyError when the faces do not form a
///        2-manifold OpenMesh can hold.
[[nodiscard]] Mesh read_mesh(const std::string& path);

/// Writes OBJ, OFF or PLY, chosen by the extension. \throw IOError.
void write_mesh(const Mesh& mesh, const std::string& path);

}  // namespace ricci

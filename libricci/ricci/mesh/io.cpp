// Interim reader on OpenMesh IO; to be replaced by the strict soup readers (issue 2).
#include "ricci/mesh/io.h"

#include <OpenMesh/Core/IO/MeshIO.hh>

#include "ricci/mesh/errors.h"

namespace ricci {

Mesh read_mesh(const std::string& path) {
  Mesh mesh;
  if (!OpenMesh::IO::read_mesh(mesh, path)) throw IOError("cannot read mesh " + path);
  return mesh;
}

void write_mesh(const Mesh& mesh, const std::string& path) {
  OpenMesh::IO::Options options;
  if (!OpenMesh::IO::write_mesh(mesh, path, options, 17)) throw IOError("cannot write mesh " + path);
}

}  // namespace ricci

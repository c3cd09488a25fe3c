#pragma once
// A polygon soup: the contents of a mesh file before any topological interpretation. Readers fill
// it, diagnose() describes it, build_mesh() turns a clean one into a ricci::Mesh.
#include <string>
#include <vector>

#include <Eigen/Core>

namespace ricci {

/// Vertex positions and polygon faces exactly as a file lists them (indices 0-based).
struct PolygonSoup {
  /// #V positions; may hold NaN/inf or unreferenced vertices (diagnose() reports them).
  std::vector<Eigen::Vector3d> positions;
  /// #F polygons, each a list of indices into `positions`, in the file's winding order.
  std::vector<std::vector<int>> faces;
  /// Source line (1-based) of each face, or empty when the format has no lines (binary files).
  std::vector<int> face_lines;
  /// Source line (1-based) of each vertex, or empty when the format has no lines.
  std::vector<int> vertex_lines;
  /// RGB of each vertex in [0, 1] (OFF with a C in its keyword, PLY red/green/blue), or empty
  /// when the file has none or some vertex lacks one.
  std::vector<Eigen::Vector3d> colours;
  /// Name of the file the soup came from ("" when built in memory); used in messages.
  std::string source;

  /// "face 12 (line 40)" or "face 12": where a face came from, for messages.
  [[nodiscard]] std::string face_where(size_t face) const {
    std::string where = "face " + std::to_string(face);
    if (face < face_lines.size() && face_lines[face] > 0)
      where += " (line " + std::to_string(face_lines[face]) + ")";
    return where;
  }
  /// "vertex 7 (line 9)" or "vertex 7".
  [[nodiscard]] std::string vertex_where(size_t vertex) const {
    std::string where = "vertex " + std::to_string(vertex);
    if (vertex < vertex_lines.size() && vertex_lines[vertex] > 0)
      where += " (line " + std::to_string(vertex_lines[vertex]) + ")";
    return where;
  }
};

}  // namespace ricci

// build_mesh(): validation by diagnose(), then orientation, triangulation and the OpenMesh build.
#include "ricci/mesh/build_mesh.h"

#include <algorithm>
#include <array>
#include <unordered_set>

#include <Eigen/Geometry>

#include "ricci/mesh/diagnose.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/topology_util.h"
#include "ricci/mesh/triangulate_polygon.h"
#include "ricci/util/edge_key.h"

namespace ricci {
namespace {

[[noreturn]] void refuse(const PolygonSoup& soup, const MeshProblem& problem) {
  const std::string message =
      soup.source.empty() ? problem.message : soup.source + ": " + problem.message;
  switch (problem.kind) {
    case MeshProblemKind::non_finite_coordinate:
    case MeshProblemKind::bad_face:
    case MeshProblemKind::repeated_index:
    case MeshProblemKind::zero_area:
      throw InvalidInputError(message);
    default:
      throw TopologyError(message);
  }
}

/// Faces re-oriented by a walk across manifold edges; every face keeps its first neighbour's
/// sense. Assumes a clean (orientable, edge-manifold, single-component) soup.
std::vector<std::vector<int>> orient_faces(const PolygonSoup& soup, int& flipped) {
  const detail::EdgeTable table = detail::build_edge_table(soup.faces, {});
  const size_t face_count = soup.faces.size();
  const std::vector<signed char> reversed = detail::colour_orientation(table, face_count, {}).flipped;
  std::vector<std::vector<int>> faces = soup.faces;
  flipped = 0;
  for (size_t f = 0; f < face_count; ++f) {
    if (!reversed[f]) continue;
    std::reverse(faces[f].begin(), faces[f].end());
    ++flipped;
  }
  bool closed = true;
  for (size_t e = 0; e < table.edge_count(); ++e) closed &= table.side_count(e) == 2;
  if (closed) {
    // Outward normals on closed surfaces: the enclosed signed volume must be positive.
    double volume = 0;
    for (const auto& face : faces)
      for (size_t k = 1; k + 1 < face.size(); ++k)
        volume +=
            soup.positions[face[0]].dot(soup.positions[face[k]].cross(soup.positions[face[k + 1]]));
    if (volume < 0) {
      for (auto& face : faces) std::reverse(face.begin(), face.end());
      flipped = static_cast<int>(face_count) - flipped;
    }
  }
  return faces;
}

/// Triangles of all faces; polygons are ear-clipped avoiding diagonals that are already edges.
std::vector<std::array<int, 3>> triangulate(const PolygonSoup& soup,
                                            const std::vector<std::vector<int>>& faces,
                                            int& polygons) {
  std::unordered_set<uint64_t> edges;
  polygons = 0;
  for (const auto& face : faces)
    if (face.size() > 3) ++polygons;
  if (polygons > 0)
    for (const auto& face : faces)
      for (size_t k = 0; k < face.size(); ++k)
        edges.insert(undirected_edge_key(face[k], face[(k + 1) % face.size()]));
  std::vector<std::array<int, 3>> triangles;
  triangles.reserve(faces.size());
  std::vector<Eigen::Vector3d> corners;
  for (const auto& face : faces) {
    if (face.size() == 3) {
      triangles.push_back({face[0], face[1], face[2]});
      continue;
    }
    corners.clear();
    for (int v : face) corners.push_back(soup.positions[v]);
    const auto pieces = triangulate_polygon(
        corners,
        [&](int i, int j) { return edges.count(undirected_edge_key(face[i], face[j])) == 0; });
    for (const auto& t : pieces) {
      triangles.push_back({face[t[0]], face[t[1]], face[t[2]]});
      for (int k = 0; k < 3; ++k)
        edges.insert(undirected_edge_key(face[t[k]], face[t[(k + 1) % 3]]));
    }
  }
  return triangles;
}

}  // namespace

MeshBuildResult build_mesh_with_report(const PolygonSoup& soup) {
  const MeshDiagnosis diagnosis = diagnose(soup);
  if (!diagnosis.problems.empty()) refuse(soup, diagnosis.problems.front());
  MeshBuildResult result;
  const std::vector<std::vector<int>> oriented = orient_faces(soup, result.faces_flipped);
  const auto triangles = triangulate(soup, oriented, result.polygons_triangulated);

  std::vector<int> new_index(soup.positions.size(), -1);
  for (const auto& t : triangles)
    for (int v : t) new_index[v] = 0;
  Mesh& mesh = result.mesh;
  mesh.reserve(soup.positions.size(), triangles.size() * 3 / 2 + 3, triangles.size());
  std::vector<VertexHandle> handles(soup.positions.size());
  for (size_t v = 0; v < soup.positions.size(); ++v) {
    if (new_index[v] < 0) {
      ++result.unreferenced_removed;
      continue;
    }
    new_index[v] = static_cast<int>(result.input_vertex.size());
    result.input_vertex.push_back(static_cast<int>(v));
    handles[v] = mesh.add_vertex(to_openmesh(soup.positions[v]));
  }
  for (size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    if (!mesh.add_face(handles[tri[0]], handles[tri[1]], handles[tri[2]]).is_valid())
      throw TopologyError((soup.source.empty() ? "" : soup.source + ": ") +
                          "OpenMesh refused triangle (" + std::to_string(tri[0]) + ", " +
                          std::to_string(tri[1]) + ", " + std::to_string(tri[2]) +
                          "): triangulating a polygon made a non-manifold edge");
  }
  return result;
}

Mesh build_mesh(const PolygonSoup& soup) { return build_mesh_with_report(soup).mesh; }

}  // namespace ricci

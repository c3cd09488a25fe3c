#include "ricci/mesh/neighbourhoods.h"

#include <algorithm>
#include <vector>

namespace ricci {
namespace {

// Number of distinct values in a small vector (sorted in place).
int count_distinct(std::vector<int>& values) {
  std::sort(values.begin(), values.end());
  return static_cast<int>(std::unique(values.begin(), values.end()) - values.begin());
}

}  // namespace

int count_non_disk_face_neighbourhoods(const Mesh& mesh) {
  int count = 0;
  std::vector<int> faces, edges, vertices;
  for (auto f : mesh.faces()) {
    faces.clear();
    for (auto v : mesh.fv_range(f)) {
      for (auto g : mesh.vf_range(v)) faces.push_back(g.idx());
    }
    const int face_count = count_distinct(faces);
    edges.clear();
    vertices.clear();
    for (int i = 0; i < face_count; ++i) {
      for (auto h : mesh.fh_range(FaceHandle(faces[i]))) {
        edges.push_back(mesh.edge_handle(h).idx());
        vertices.push_back(mesh.to_vertex_handle(h).idx());
      }
    }
    if (count_distinct(vertices) - count_distinct(edges) + face_count != 1) ++count;
  }
  return count;
}

}  // namespace ricci

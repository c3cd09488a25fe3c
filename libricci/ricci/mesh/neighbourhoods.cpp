#include "ricci/mesh/neighbourhoods.h"

#include <algorithm>
#include <vector>

namespace ricci {
namespace {

// Counts distinct indices with a per-index stamp (no sorting: this runs once per face).
struct DistinctCounter {
  std::vector<int> stamp;
  int current = 0, count = 0;

  explicit DistinctCounter(std::size_t size) : stamp(size, -1) {}
  void start(int id) {
    current = id;
    count = 0;
  }
  bool add(int index) {
    if (stamp[index] == current) return false;
    stamp[index] = current;
    ++count;
    return true;
  }
};

}  // namespace

std::vector<char> non_disk_face_neighbourhoods(const Mesh& mesh) {
  DistinctCounter faces(mesh.n_faces()), edges(mesh.n_edges()), vertices(mesh.n_vertices());
  std::vector<char> flagged(mesh.n_faces(), 0);
  for (auto f : mesh.faces()) {
    faces.start(f.idx());
    edges.start(f.idx());
    vertices.start(f.idx());
    for (auto v : mesh.fv_range(f)) {
      for (auto g : mesh.vf_range(v)) {
        if (!faces.add(g.idx())) continue;
        for (auto h : mesh.fh_range(g)) {
          edges.add(mesh.edge_handle(h).idx());
          vertices.add(mesh.to_vertex_handle(h).idx());
        }
      }
    }
    flagged[f.idx()] = vertices.count - edges.count + faces.count != 1;
  }
  return flagged;
}

int count_non_disk_face_neighbourhoods(const Mesh& mesh) {
  const std::vector<char> flagged = non_disk_face_neighbourhoods(mesh);
  return static_cast<int>(std::count(flagged.begin(), flagged.end(), 1));
}

}  // namespace ricci

#include "ricci/mesh/boundary_loops.h"

namespace ricci {

std::vector<std::vector<HalfedgeHandle>> find_boundary_loops(const Mesh& mesh) {
  std::vector<std::vector<HalfedgeHandle>> loops;
  std::vector<char> seen(mesh.n_halfedges(), 0);
  for (auto h : mesh.halfedges()) {
    if (!mesh.is_boundary(h) || seen[h.idx()]) continue;
    std::vector<HalfedgeHandle> loop;
    for (auto g = h; !seen[g.idx()]; g = mesh.next_halfedge_handle(g)) {
      seen[g.idx()] = 1;
      loop.push_back(g);
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

}  // namespace ricci

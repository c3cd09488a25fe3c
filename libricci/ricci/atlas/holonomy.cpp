#include "ricci/atlas/holonomy.h"

namespace ricci {
namespace {

/// Crossing rules of the cut: for each cut edge, its arc's side pairing and which face is on
/// the arc's left (the side the pairing maps from).
struct CutCrossings {
  std::vector<int> arc_of_edge;
  std::vector<int> left_face_of_edge;

  CutCrossings(const Mesh& mesh, const AffineAtlas& atlas)
      : arc_of_edge(mesh.n_edges(), -1), left_face_of_edge(mesh.n_edges(), -1) {
    for (size_t a = 0; a < atlas.side_pairings.size(); ++a) {
      for (auto h : atlas.side_pairings[a].halfedges) {
        arc_of_edge[mesh.edge_handle(h).idx()] = static_cast<int>(a);
        left_face_of_edge[mesh.edge_handle(h).idx()] = mesh.face_handle(h).idx();
      }
    }
  }
};

/// Develops clockwise around from_vertex(start) from face(start) until face(stop) (both
/// outgoing halfedges of the same vertex), composing crossings into `development`.
void turn_clockwise(const Mesh& mesh, const AffineAtlas& atlas, const CutCrossings& cut,
                    HalfedgeHandle start, HalfedgeHandle stop, RigidMotion2& development) {
  for (auto g = start; g != stop;) {
    const int e = mesh.edge_handle(g).idx();
    const int arc = cut.arc_of_edge[e];
    if (arc >= 0) {
      const RigidMotion2& m = atlas.side_pairings[arc].motion;
      // Leaving the arc's left face for its right face: the right face's central copy sits
      // across the paired side, so it is brought back by the inverse pairing (and vice versa).
      development = development.after(
          mesh.face_handle(g).idx() == cut.left_face_of_edge[e] ? m.inverse() : m);
    }
    g = mesh.next_halfedge_handle(mesh.opposite_halfedge_handle(g));
  }
}

}  // namespace

std::vector<RigidMotion2> loop_holonomies(const Mesh& mesh, const AffineAtlas& atlas) {
  std::vector<RigidMotion2> result;
  if (atlas.cut.boundary_loop_count > 0) return result;
  const CutCrossings cut(mesh, atlas);
  const VertexHandle root = atlas.cut.root;
  const HalfedgeHandle reference = *mesh.voh_range(root).begin();
  for (const CutPath& loop : atlas.cut.loops) {
    const auto& hs = loop.halfedges;
    RigidMotion2 development;
    turn_clockwise(mesh, atlas, cut, reference, hs.front(), development);
    for (size_t k = 0; k + 1 < hs.size(); ++k) {
      // Left side of the path at to_vertex(hs[k]): clockwise from face(hs[k]) to face(hs[k+1]).
      turn_clockwise(mesh, atlas, cut, mesh.next_halfedge_handle(hs[k]), hs[k + 1], development);
    }
    turn_clockwise(mesh, atlas, cut, mesh.next_halfedge_handle(hs.back()), reference, development);
    result.push_back(development);
  }
  return result;
}

RigidMotion2 word_holonomy(const std::vector<RigidMotion2>& loop_holonomy,
                           const std::vector<PolygonLetter>& word) {
  RigidMotion2 product;
  for (const auto& l : word) {
    if (l.kind != PolygonLetter::Kind::loop) continue;
    const RigidMotion2& m = loop_holonomy.at(static_cast<size_t>(l.index));
    product = product.after(l.sign > 0 ? m : m.inverse());
  }
  return product;
}

}  // namespace ricci

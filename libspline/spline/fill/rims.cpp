// Rims: closed loops of domain edges with exactly one domain face (hole_fill.h).
#include <algorithm>
#include <string>

#include "ricci/mesh/errors.h"
#include "ricci/topology/slice.h"
#include "spline/fill/hole_fill.h"

namespace spline {
namespace {

int kind_rank(Rim::Kind kind) {
  switch (kind) {
    case Rim::Kind::cone_hole: return 0;
    case Rim::Kind::boundary: return 1;
    case Rim::Kind::excluded: return 2;
  }
  return 3;
}

Rim::Kind kind_of_rank(int rank) {
  return rank == 0 ? Rim::Kind::cone_hole : rank == 1 ? Rim::Kind::boundary : Rim::Kind::excluded;
}

// Which faces are kept (domain, not covered) and, for the others, the rank of the kind of hole
// they belong to.
struct Regions {
  std::vector<char> kept;
  std::vector<int> rank;  // by face, for faces not kept
};

// A halfedge whose face is kept and whose opposite is not (boundary, outside, covered).
bool is_rim_halfedge(const Regions& regions, const ricci::Mesh& mesh, ricci::HalfedgeHandle h) {
  if (mesh.is_boundary(h) || !regions.kept[mesh.face_handle(h).idx()]) return false;
  const auto o = mesh.opposite_halfedge_handle(h);
  return mesh.is_boundary(o) || !regions.kept[mesh.face_handle(o).idx()];
}

int rank_of(const Regions& regions, const ricci::Mesh& mesh, ricci::HalfedgeHandle h) {
  const auto o = mesh.opposite_halfedge_handle(h);
  return mesh.is_boundary(o) ? kind_rank(Rim::Kind::boundary)
                             : regions.rank[mesh.face_handle(o).idx()];
}

// Corner k of h's face opposite h: h runs from corner k + 1 to corner k + 2 (hole_fill.h).
RimEdge rim_edge_of(const ricci::Mesh& mesh, ricci::HalfedgeHandle h) {
  const auto f = mesh.face_handle(h);
  const auto hs = ricci::face_halfedges(mesh, f);
  for (int i = 0; i < 3; ++i) {
    if (hs[i] == h) return {f.idx(), (i + 1) % 3};
  }
  throw ricci::TopologyError("find_rims: halfedge " + std::to_string(h.idx()) +
                             " is not among its face's halfedges");
}

// The rim halfedge leaving h's end vertex: turn through kept faces around it until the edge
// across has no kept face (the first such edge in the sector next to h's face).
ricci::HalfedgeHandle next_rim_halfedge(const Regions& regions, const ricci::Mesh& mesh,
                                        ricci::HalfedgeHandle h) {
  auto c = mesh.next_halfedge_handle(h);
  const auto valence = mesh.valence(mesh.to_vertex_handle(h));
  for (std::size_t step = 0; step <= valence; ++step) {
    if (is_rim_halfedge(regions, mesh, c)) return c;
    c = mesh.next_halfedge_handle(mesh.opposite_halfedge_handle(c));
  }
  throw ricci::TopologyError("find_rims: no rim edge leaves vertex " +
                             std::to_string(mesh.to_vertex_handle(h).idx()));
}

Regions initial_regions(const ManifoldSplineSpace& space, const ricci::Mesh& mesh) {
  Regions regions;
  regions.kept.assign(mesh.n_faces(), 0);
  regions.rank.assign(mesh.n_faces(), 3);
  for (auto f : mesh.faces()) {
    const int i = f.idx();
    regions.kept[i] = space.in_domain(i) ? 1 : 0;
    if (!regions.kept[i]) {
      regions.rank[i] = kind_rank(space.atlas().in_domain[i] ? Rim::Kind::excluded
                                                              : Rim::Kind::cone_hole);
    }
  }
  return regions;
}

// One layer: every kept face touching a rim vertex is covered, with the rank of that vertex's
// holes.
void grow_once(Regions& regions, const ricci::Mesh& mesh) {
  std::vector<int> vertex_rank(mesh.n_vertices(), -1);
  for (auto h : mesh.halfedges()) {
    if (!is_rim_halfedge(regions, mesh, h)) continue;
    const int rank = rank_of(regions, mesh, h);
    for (auto v : {mesh.from_vertex_handle(h), mesh.to_vertex_handle(h)}) {
      int& r = vertex_rank[v.idx()];
      r = r < 0 ? rank : std::min(r, rank);
    }
  }
  for (auto v : mesh.vertices()) {
    if (vertex_rank[v.idx()] < 0) continue;
    for (auto f : mesh.vf_range(v)) {
      if (!regions.kept[f.idx()]) continue;
      regions.kept[f.idx()] = 0;
      regions.rank[f.idx()] = vertex_rank[v.idx()];
    }
  }
  // Faces covered through several vertices keep the smallest rank.
  for (auto v : mesh.vertices()) {
    if (vertex_rank[v.idx()] < 0) continue;
    for (auto f : mesh.vf_range(v)) {
      int& r = regions.rank[f.idx()];
      r = std::min(r, vertex_rank[v.idx()]);
    }
  }
}

// Covered domain faces reachable from the faces across the rim through covered faces.
std::vector<int> covered_inside(const ManifoldSplineSpace& space, const Regions& regions,
                                const ricci::Mesh& mesh,
                                const std::vector<ricci::HalfedgeHandle>& loop) {
  auto covered = [&](int f) { return !regions.kept[f] && space.in_domain(f); };
  std::vector<char> seen(mesh.n_faces(), 0);
  std::vector<int> stack, faces;
  for (auto h : loop) {
    const auto o = mesh.opposite_halfedge_handle(h);
    if (mesh.is_boundary(o)) continue;
    const int f = mesh.face_handle(o).idx();
    if (covered(f) && !seen[f]) {
      seen[f] = 1;
      stack.push_back(f);
    }
  }
  while (!stack.empty()) {
    const int f = stack.back();
    stack.pop_back();
    faces.push_back(f);
    for (auto g : mesh.ff_range(mesh.face_handle(f))) {
      if (covered(g.idx()) && !seen[g.idx()]) {
        seen[g.idx()] = 1;
        stack.push_back(g.idx());
      }
    }
  }
  std::sort(faces.begin(), faces.end());
  return faces;
}

}  // namespace

Eigen::Vector3d rim_edge_barycentric(const RimEdge& edge, double t) {
  Eigen::Vector3d bary = Eigen::Vector3d::Zero();
  bary[rim_edge_start_corner(edge)] = 1.0 - t;
  bary[rim_edge_end_corner(edge)] = t;
  return bary;
}

std::vector<int> rim_vertices(const Rim& rim, const ricci::Mesh& mesh) {
  std::vector<int> vertices;
  vertices.reserve(rim.edges.size());
  for (const RimEdge& e : rim.edges) {
    const auto hs = ricci::face_halfedges(mesh, mesh.face_handle(e.face));
    vertices.push_back(mesh.to_vertex_handle(hs[rim_edge_start_corner(e)]).idx());
  }
  return vertices;
}

std::vector<Rim> find_rims(const ManifoldSplineSpace& space, const ricci::Mesh& mesh,
                           const FindRimsOptions& options) {
  if (static_cast<int>(mesh.n_faces()) != space.face_count()) {
    throw ricci::InvalidInputError("find_rims: the mesh has " + std::to_string(mesh.n_faces()) +
                                   " faces, the spline space " +
                                   std::to_string(space.face_count()));
  }
  if (options.grow < 0) {
    throw ricci::InvalidInputError("find_rims: grow must be >= 0, got " +
                                   std::to_string(options.grow));
  }
  Regions regions = initial_regions(space, mesh);
  for (int layer = 0; layer < options.grow; ++layer) grow_once(regions, mesh);

  std::vector<char> visited(mesh.n_halfedges(), 0);
  std::vector<Rim> rims;
  // Faces ascending, so each loop starts at its smallest face's rim edge.
  for (int face : space.domain_faces()) {
    for (auto h : ricci::face_halfedges(mesh, mesh.face_handle(face))) {
      if (visited[h.idx()] || !is_rim_halfedge(regions, mesh, h)) continue;
      std::vector<ricci::HalfedgeHandle> loop;
      int rank = 3;
      for (auto c = h; !visited[c.idx()]; c = next_rim_halfedge(regions, mesh, c)) {
        visited[c.idx()] = 1;
        loop.push_back(c);
        rank = std::min(rank, rank_of(regions, mesh, c));
      }
      Rim rim;
      rim.kind = kind_of_rank(rank);
      for (auto c : loop) rim.edges.push_back(rim_edge_of(mesh, c));
      rim.covered_faces = covered_inside(space, regions, mesh, loop);
      rims.push_back(std::move(rim));
    }
  }
  std::stable_sort(rims.begin(), rims.end(), [](const Rim& a, const Rim& b) {
    return kind_rank(a.kind) < kind_rank(b.kind);
  });
  return rims;
}

}  // namespace spline

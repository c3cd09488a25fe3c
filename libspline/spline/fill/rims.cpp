// Rims: closed loops of domain edges with exactly one domain face (hole_fill.h).
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>

#include "ricci/mesh/boundary_loops.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/topology_util.h"
#include "ricci/topology/slice.h"
#include "ricci/util/cross2d.h"
#include "spline/fill/hole_fill.h"
#include "spline/fill/rims.h"

namespace spline {
namespace {

int kind_rank(Rim::Kind kind) {
  switch (kind) {
    case Rim::Kind::cone_hole:
      return 0;
    case Rim::Kind::boundary:
      return 1;
    case Rim::Kind::excluded:
      return 2;
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

Regions initial_regions(const std::vector<char>& domain, const std::vector<char>& atlas_domain,
                        const std::vector<char>& boundary_faces) {
  Regions regions;
  regions.kept.assign(domain.size(), 0);
  regions.rank.assign(domain.size(), 3);
  for (std::size_t i = 0; i < domain.size(); ++i) {
    const bool beyond = !boundary_faces.empty() && boundary_faces[i];
    regions.kept[i] = domain[i] && !beyond ? 1 : 0;
    if (beyond) {
      regions.rank[i] = kind_rank(Rim::Kind::boundary);
    } else if (!regions.kept[i]) {
      regions.rank[i] = kind_rank(atlas_domain[i] ? Rim::Kind::excluded : Rim::Kind::cone_hole);
    }
  }
  return regions;
}

// The mesh's boundary loops: by halfedge, the loop of a boundary halfedge (-1 otherwise).
struct Loops {
  std::vector<int> of_halfedge;
  int count = 0;
};

Loops boundary_loops(const ricci::Mesh& mesh) {
  Loops loops;
  loops.of_halfedge.assign(mesh.n_halfedges(), -1);
  for (const auto& loop : ricci::find_boundary_loops(mesh)) {
    for (const auto h : loop) loops.of_halfedge[h.idx()] = loops.count;
    ++loops.count;
  }
  return loops;
}

// Holes: connected components of the faces not kept and the boundary loops, joined across
// edges (holes meeting at a vertex only stay apart: that vertex is a pinch, see hole_is_disk).
struct Holes {
  std::vector<int> of_face;  // by face: its hole, -1 for kept faces
  std::vector<int> of_loop;  // by boundary loop
  std::vector<int> rank;     // by hole: smallest rank of its faces and loops
  int count = 0;
};

Holes label_holes(const Regions& regions, const ricci::Mesh& mesh, const Loops& loops) {
  const int faces = static_cast<int>(mesh.n_faces());
  const auto nodes = static_cast<std::size_t>(faces + loops.count);
  ricci::detail::DisjointSets sets(nodes);
  auto node = [&](ricci::HalfedgeHandle h) {  // the hole side of h, -1 when kept
    if (mesh.is_boundary(h)) return faces + loops.of_halfedge[h.idx()];
    const int f = mesh.face_handle(h).idx();
    return regions.kept[f] ? -1 : f;
  };
  for (auto e : mesh.edges()) {
    const int a = node(mesh.halfedge_handle(e, 0)), b = node(mesh.halfedge_handle(e, 1));
    if (a >= 0 && b >= 0) sets.unite(a, b);
  }
  Holes holes;
  holes.of_face.assign(static_cast<std::size_t>(faces), -1);
  holes.of_loop.assign(static_cast<std::size_t>(loops.count), -1);
  std::vector<int> label(nodes, -1);
  auto label_of = [&](int i) {
    int& l = label[sets.find(i)];
    if (l < 0) {
      l = holes.count++;
      holes.rank.push_back(3);
    }
    return l;
  };
  for (int f = 0; f < faces; ++f) {
    if (regions.kept[f]) continue;
    const int l = holes.of_face[f] = label_of(f);
    holes.rank[l] = std::min(holes.rank[l], regions.rank[f]);
  }
  for (int i = 0; i < loops.count; ++i) {
    const int l = holes.of_loop[i] = label_of(faces + i);
    holes.rank[l] = std::min(holes.rank[l], kind_rank(Rim::Kind::boundary));
  }
  return holes;
}

// Every face of a hole takes the hole's rank (its smallest): the faces the spline space
// excluded around the cone's one-ring (at genus 6-9 the flat metric shrinks them below the size
// rules, hundreds of faces) are the cone hole, whose rim then lies on excluded faces only.
void share_hole_ranks(Regions& regions, const ricci::Mesh& mesh, const Loops& loops) {
  const Holes holes = label_holes(regions, mesh, loops);
  for (std::size_t f = 0; f < holes.of_face.size(); ++f) {
    if (holes.of_face[f] >= 0) regions.rank[f] = holes.rank[holes.of_face[f]];
  }
}

// The hole on the far side of h (its opposite's face or boundary loop), -1 when that is kept.
int hole_across(const Holes& holes, const Loops& loops, const ricci::Mesh& mesh,
                ricci::HalfedgeHandle h) {
  const auto o = mesh.opposite_halfedge_handle(h);
  if (mesh.is_boundary(o)) return holes.of_loop[loops.of_halfedge[o.idx()]];
  return holes.of_face[mesh.face_handle(o).idx()];
}

// The holes around a vertex, in turn order (one entry per face slot; boundary gaps give their
// loop's hole, kept faces -1).
std::vector<int> holes_around(const Holes& holes, const Loops& loops, const ricci::Mesh& mesh,
                              ricci::VertexHandle v) {
  std::vector<int> around;
  for (auto h : mesh.voh_range(v)) {
    around.push_back(mesh.is_boundary(h) ? holes.of_loop[loops.of_halfedge[h.idx()]]
                                         : holes.of_face[mesh.face_handle(h).idx()]);
  }
  return around;
}

// By hole: whether a patch can close it. The hole must be a disk: no pinch vertex (where the
// kept faces around a vertex form more than one fan, or two holes meet) and Euler
// characteristic V - E + F + (boundary loops, each capped by a disk) = 1. A disk's rim is then
// one simple loop sharing no vertex with another rim.
std::vector<char> holes_are_disks(const Holes& holes, const Loops& loops, const ricci::Mesh& mesh) {
  std::vector<int> chi(static_cast<std::size_t>(holes.count), 0);
  std::vector<char> pinched(static_cast<std::size_t>(holes.count), 0);
  for (int f = 0; f < static_cast<int>(holes.of_face.size()); ++f) {
    if (holes.of_face[f] >= 0) ++chi[holes.of_face[f]];
  }
  for (int l : holes.of_loop) ++chi[l];
  std::vector<int> touched;
  for (auto v : mesh.vertices()) {
    const auto around = holes_around(holes, loops, mesh, v);
    touched.assign(around.begin(), around.end());
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    int changes = 0;
    for (std::size_t i = 0; i < around.size(); ++i)
      changes += around[i] != around[(i + 1) % around.size()];
    for (int l : touched) {
      if (l < 0) continue;
      ++chi[l];
      // A hole and the kept faces alternate once (two changes); all faces in one hole: none.
      if (changes > 2) pinched[l] = 1;
    }
  }
  for (auto e : mesh.edges()) {
    const int a = hole_across(holes, loops, mesh, mesh.halfedge_handle(e, 0));
    const int b = hole_across(holes, loops, mesh, mesh.halfedge_handle(e, 1));
    if (a >= 0) --chi[a];
    if (b >= 0 && b != a) --chi[b];
  }
  std::vector<char> disk(static_cast<std::size_t>(holes.count), 0);
  for (int l = 0; l < holes.count; ++l) disk[l] = !pinched[l] && chi[l] == 1;
  return disk;
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

// Kept faces cut off from the largest kept region by a grown hole (a face or two enclosed by
// covered faces) are covered too: a rim around such an island would be filled by a disk over
// the island. Their rank is the smallest rank of the faces around them.
void cover_islands(Regions& regions, const ricci::Mesh& mesh) {
  std::vector<int> component(mesh.n_faces(), -1);
  std::vector<int> sizes;
  for (auto f : mesh.faces()) {
    if (!regions.kept[f.idx()] || component[f.idx()] >= 0) continue;
    const int c = static_cast<int>(sizes.size());
    sizes.push_back(0);
    std::vector<int> stack{f.idx()};
    component[f.idx()] = c;
    while (!stack.empty()) {
      const int g = stack.back();
      stack.pop_back();
      ++sizes[c];
      for (auto h : mesh.ff_range(mesh.face_handle(g))) {
        if (regions.kept[h.idx()] && component[h.idx()] < 0) {
          component[h.idx()] = c;
          stack.push_back(h.idx());
        }
      }
    }
  }
  if (sizes.size() < 2) return;
  const int largest =
      static_cast<int>(std::max_element(sizes.begin(), sizes.end()) - sizes.begin());
  std::vector<int> island_rank(sizes.size(), 3);
  for (auto f : mesh.faces()) {
    const int c = component[f.idx()];
    if (c < 0 || c == largest) continue;
    for (auto g : mesh.ff_range(f)) {
      if (!regions.kept[g.idx()]) island_rank[c] = std::min(island_rank[c], regions.rank[g.idx()]);
    }
  }
  for (auto f : mesh.faces()) {
    const int c = component[f.idx()];
    if (c < 0 || c == largest) continue;
    regions.kept[f.idx()] = 0;
    regions.rank[f.idx()] = island_rank[c];
  }
}

// The one hole kept face f can join while that hole stays a disk apart from every other hole,
// or -1. f's sides on holes must all be on one hole and form one arc of f's boundary: one edge
// (f's third vertex then touches no hole) or two or three edges; no vertex of f may touch
// another hole. Each such step keeps the hole a disk, its rim simple and the rims disjoint.
int joinable_hole(const Holes& holes, const Loops& loops, const ricci::Mesh& mesh, int face) {
  int hole = -1, sides = 0;
  ricci::HalfedgeHandle side;
  for (auto h : ricci::face_halfedges(mesh, mesh.face_handle(face))) {
    const int l = hole_across(holes, loops, mesh, h);
    if (l < 0) continue;
    if (hole >= 0 && l != hole) return -1;
    hole = l;
    side = h;
    ++sides;
  }
  if (sides == 0) return -1;
  for (auto v : mesh.fv_range(mesh.face_handle(face))) {
    for (int l : holes_around(holes, loops, mesh, v)) {
      if (l >= 0 && l != hole) return -1;
    }
  }
  if (sides == 1) {
    const auto opposite = mesh.to_vertex_handle(mesh.next_halfedge_handle(side));
    for (int l : holes_around(holes, loops, mesh, opposite)) {
      if (l >= 0) return -1;
    }
  }
  return hole;
}

// Covers the candidate faces one at a time (ascending, repeated until none joins) where
// joinable_hole allows it.
void grow_face_by_face(Regions& regions, const ricci::Mesh& mesh, const Loops& loops,
                       const std::vector<int>& candidates) {
  Holes holes = label_holes(regions, mesh, loops);
  for (bool changed = true; changed;) {
    changed = false;
    for (int f : candidates) {
      if (!regions.kept[f]) continue;
      const int hole = joinable_hole(holes, loops, mesh, f);
      if (hole < 0) continue;
      regions.kept[f] = 0;
      regions.rank[f] = holes.rank[hole];
      holes.of_face[f] = hole;
      changed = true;
    }
  }
}

// One layer (grow_once and cover_islands), undone and redone face by face on every hole it
// leaves no disk (or that merges a boundary loop's hole with another, unless allowed).
void grow_layer(Regions& regions, const ricci::Mesh& mesh, const Loops& loops,
                const RimMergeOptions& merge) {
  const std::vector<char> before = regions.kept;
  const Holes old_holes = label_holes(regions, mesh, loops);
  grow_once(regions, mesh);
  cover_islands(regions, mesh);
  const Holes holes = label_holes(regions, mesh, loops);
  std::vector<char> disk = holes_are_disks(holes, loops, mesh);
  if (!merge.boundary_loops) {
    // A new hole joining several old ones, one of them holding a boundary loop: undone.
    std::vector<char> old_has_loop(static_cast<std::size_t>(old_holes.count), 0);
    for (int l : old_holes.of_loop) old_has_loop[l] = 1;
    std::vector<int> first(static_cast<std::size_t>(holes.count), -1);
    std::vector<char> has_loop(static_cast<std::size_t>(holes.count), 0),
        joins(static_cast<std::size_t>(holes.count), 0);
    auto note = [&](int now, int was) {
      if (was < 0) return;
      has_loop[now] = has_loop[now] || old_has_loop[was];
      if (first[now] < 0) first[now] = was;
      joins[now] = joins[now] || first[now] != was;
    };
    for (std::size_t f = 0; f < before.size(); ++f) {
      if (holes.of_face[f] >= 0) note(holes.of_face[f], old_holes.of_face[f]);
    }
    for (std::size_t l = 0; l < holes.of_loop.size(); ++l)
      note(holes.of_loop[l], old_holes.of_loop[l]);
    for (int h = 0; h < holes.count; ++h) {
      if (joins[h] && has_loop[h]) disk[h] = 0;
    }
  }
  std::vector<int> undone;
  for (int f = 0; f < static_cast<int>(before.size()); ++f) {
    if (before[f] && !regions.kept[f] && !disk[holes.of_face[f]]) {
      regions.kept[f] = 1;
      regions.rank[f] = 3;
      undone.push_back(f);
    }
  }
  if (!undone.empty()) grow_face_by_face(regions, mesh, loops, undone);
}

// The largest factor between face f's chart scale and an edge neighbour's (1 when no
// neighbour has a scale).
double worst_scale_ratio(const std::vector<double>& chart_scale, const ricci::Mesh& mesh, int f) {
  double worst = 1.0;
  const double s = chart_scale[static_cast<std::size_t>(f)];
  if (!(s > 0.0)) return worst;
  for (auto g : mesh.ff_range(mesh.face_handle(f))) {
    const double t = chart_scale[static_cast<std::size_t>(g.idx())];
    if (t > 0.0) worst = std::max(worst, std::max(s / t, t / s));
  }
  return worst;
}

// True when a face on the cone hole's rim is badly conditioned or folded
// (FindRimsOptions::max_cone_rim_scale_ratio, max_cone_rim_normal_step_deg); marks the rim's
// vertices in on_rim.
bool cone_rim_is_poor(const Regions& regions, const ricci::Mesh& mesh,
                      const std::vector<double>& chart_scale,
                      const std::function<double(int)>& normal_step_deg,
                      const FindRimsOptions& options, std::vector<char>& on_rim) {
  const bool by_scale = !chart_scale.empty() && options.max_cone_rim_scale_ratio > 1.0;
  const int cone = kind_rank(Rim::Kind::cone_hole);
  bool poor = false;
  on_rim.assign(mesh.n_vertices(), 0);
  for (auto h : mesh.halfedges()) {
    if (!is_rim_halfedge(regions, mesh, h) || rank_of(regions, mesh, h) != cone) continue;
    on_rim[mesh.from_vertex_handle(h).idx()] = on_rim[mesh.to_vertex_handle(h).idx()] = 1;
    if (poor) continue;
    const int f = mesh.face_handle(h).idx();
    poor = (by_scale &&
            worst_scale_ratio(chart_scale, mesh, f) > options.max_cone_rim_scale_ratio) ||
           (normal_step_deg && normal_step_deg(f) > options.max_cone_rim_normal_step_deg);
  }
  return poor;
}

// Extra layers of the cone hole: while its rim is poor (cone_rim_is_poor; and for the first
// extra_cone_layers layers, and cone_margin_layers more after the last poor one), every kept
// face touching a vertex of its rim joins it face by face (grow_face_by_face keeps every hole a
// disk apart from the others); a layer that would cover more than the cover fraction of the
// domain is undone and the growth stops. Past max_cone_layers / max_cone_cover_fraction the
// growth goes on within cone_reach_layers / cone_reach_cover_fraction, and is undone back to
// where those caps stopped it unless the rim comes clear.
void grow_cone_hole_while_distorted(Regions& regions, const ricci::Mesh& mesh, const Loops& loops,
                                    const std::vector<char>& domain,
                                    const std::vector<double>& chart_scale,
                                    const std::function<double(int)>& normal_step_deg,
                                    const FindRimsOptions& options) {
  const bool by_scale = !chart_scale.empty() && options.max_cone_rim_scale_ratio > 1.0;
  if (!by_scale && !normal_step_deg && options.extra_cone_layers <= 0) return;
  const int cone = kind_rank(Rim::Kind::cone_hole);
  const auto domain_faces = static_cast<double>(std::count(domain.begin(), domain.end(), 1));
  const int layers = std::max(options.max_cone_layers, options.cone_reach_layers);
  const double fraction =
      std::max(options.max_cone_cover_fraction, options.cone_reach_cover_fraction);
  std::optional<Regions> at_caps;  // the hole where the max_cone_* caps stopped it
  int margin = 0;  // layers since the rim last had a poor face; > 0 at the end: it came clear
  std::vector<char> on_rim;
  for (int layer = 0; layer < layers; ++layer) {
    if (layer == options.max_cone_layers && !at_caps) at_caps = regions;
    const bool poor =
        cone_rim_is_poor(regions, mesh, chart_scale, normal_step_deg, options, on_rim);
    if (poor || layer < options.extra_cone_layers) {
      margin = 0;
    } else if (layer == 0 || margin++ >= options.cone_margin_layers) {
      break;  // a hole that was never poor gets no margin
    }
    std::vector<int> candidates;
    for (auto v : mesh.vertices()) {
      if (!on_rim[v.idx()]) continue;
      for (auto f : mesh.vf_range(v)) {
        if (regions.kept[f.idx()]) candidates.push_back(f.idx());
      }
    }
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    Regions before = regions;
    grow_face_by_face(regions, mesh, loops, candidates);
    std::ptrdiff_t covered = 0;
    for (std::size_t f = 0; f < domain.size(); ++f)
      covered += domain[f] && !regions.kept[f] && regions.rank[f] == cone;
    if (covered > fraction * domain_faces) {
      regions = std::move(before);
      break;
    }
    if (!at_caps && covered > options.max_cone_cover_fraction * domain_faces)
      at_caps = std::move(before);
  }
  if (margin == 0 && at_caps) regions = std::move(*at_caps);
}

// FindRimsOptions::cone_rim_vertices_to_cover: the kept faces around those vertices join the
// cone hole where grow_face_by_face allows it.
void cover_around_cone_rim_vertices(Regions& regions, const ricci::Mesh& mesh, const Loops& loops,
                                    const std::vector<int>& vertices) {
  if (vertices.empty()) return;
  const int cone = kind_rank(Rim::Kind::cone_hole);
  std::vector<int> candidates;
  for (int v : vertices) {
    if (v < 0 || v >= static_cast<int>(mesh.n_vertices())) {
      throw ricci::InvalidInputError("find_rims: cone rim vertex " + std::to_string(v) +
                                     " is not a vertex of the mesh");
    }
    bool on_cone_hole = false;
    for (auto f : mesh.vf_range(mesh.vertex_handle(v))) {
      on_cone_hole = on_cone_hole || (!regions.kept[f.idx()] && regions.rank[f.idx()] == cone);
    }
    if (!on_cone_hole) continue;
    for (auto f : mesh.vf_range(mesh.vertex_handle(v))) {
      if (regions.kept[f.idx()]) candidates.push_back(f.idx());
    }
  }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  grow_face_by_face(regions, mesh, loops, candidates);
}

// Covered domain faces reachable from the faces across the rim through the hole's faces.
std::vector<int> covered_inside(const std::vector<char>& domain, const Regions& regions,
                                const ricci::Mesh& mesh,
                                const std::vector<ricci::HalfedgeHandle>& loop) {
  // Through every face of the hole: domain faces past a band of faces outside the domain
  // (kept faces around the cone's one-ring, an island inside the excluded faces at genus 6-9)
  // are covered too, or they would be tessellated inside the patch.
  auto covered = [&](int f) { return !regions.kept[f]; };
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
    if (domain[f]) faces.push_back(f);
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

const char* rim_kind_id(Rim::Kind kind) {
  switch (kind) {
    case Rim::Kind::cone_hole:
      return "cone_hole";
    case Rim::Kind::boundary:
      return "boundary";
    case Rim::Kind::excluded:
      return "excluded";
  }
  return "rim";
}

const char* rim_kind_description(Rim::Kind kind) {
  switch (kind) {
    case Rim::Kind::cone_hole:
      return "cone hole";
    case Rim::Kind::boundary:
      return "boundary loop";
    case Rim::Kind::excluded:
      return "excluded-face hole";
  }
  return "rim";
}

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

std::vector<Rim> find_rims(const ricci::Mesh& mesh, const std::vector<char>& domain,
                           const std::vector<char>& atlas_domain, const FindRimsOptions& options,
                           const RimMergeOptions& merge, const std::vector<double>& chart_scale,
                           const std::function<double(int)>& normal_step_deg) {
  const std::size_t faces = mesh.n_faces();
  if (domain.size() != faces || atlas_domain.size() != faces ||
      !(chart_scale.empty() || chart_scale.size() == faces) ||
      !(options.boundary_faces.empty() || options.boundary_faces.size() == faces)) {
    throw ricci::InvalidInputError("find_rims: the mesh has " + std::to_string(faces) +
                                   " faces, the domain masks " + std::to_string(domain.size()) +
                                   " and " + std::to_string(atlas_domain.size()) +
                                   ", the chart scales " + std::to_string(chart_scale.size()) +
                                   ", the boundary faces " +
                                   std::to_string(options.boundary_faces.size()));
  }
  if (options.grow < 0) {
    throw ricci::InvalidInputError("find_rims: grow must be >= 0, got " +
                                   std::to_string(options.grow));
  }
  Regions regions = initial_regions(domain, atlas_domain, options.boundary_faces);
  const Loops loops = boundary_loops(mesh);
  share_hole_ranks(regions, mesh, loops);
  for (int layer = 0; layer < options.grow; ++layer) grow_layer(regions, mesh, loops, merge);
  share_hole_ranks(regions, mesh, loops);
  grow_cone_hole_while_distorted(regions, mesh, loops, domain, chart_scale, normal_step_deg,
                                 options);
  cover_around_cone_rim_vertices(regions, mesh, loops, options.cone_rim_vertices_to_cover);

  std::vector<char> visited(mesh.n_halfedges(), 0);
  std::vector<Rim> rims;
  // Faces ascending, so each loop starts at its smallest face's rim edge.
  for (auto fh : mesh.faces()) {
    if (!domain[fh.idx()]) continue;
    for (auto h : ricci::face_halfedges(mesh, fh)) {
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
      rim.covered_faces = covered_inside(domain, regions, mesh, loop);
      rims.push_back(std::move(rim));
    }
  }
  std::stable_sort(rims.begin(), rims.end(), [](const Rim& a, const Rim& b) {
    return kind_rank(a.kind) < kind_rank(b.kind);
  });
  return rims;
}

std::vector<Rim> find_rims(const ManifoldSplineSpace& space, const ricci::Mesh& mesh,
                           const FindRimsOptions& options) {
  if (static_cast<int>(mesh.n_faces()) != space.face_count()) {
    throw ricci::InvalidInputError("find_rims: the mesh has " + std::to_string(mesh.n_faces()) +
                                   " faces, the spline space " +
                                   std::to_string(space.face_count()));
  }
  std::vector<char> domain(mesh.n_faces(), 0);
  for (int f = 0; f < space.face_count(); ++f) domain[f] = space.in_domain(f) ? 1 : 0;
  return find_rims(mesh, domain, space.atlas().in_domain, options, {},
                   chart_scale_by_face(space, mesh));
}

std::vector<double> chart_scale_by_face(const ManifoldSplineSpace& space, const ricci::Mesh& mesh) {
  if (static_cast<int>(mesh.n_faces()) != space.face_count()) {
    throw ricci::InvalidInputError("chart_scale_by_face: the mesh has " +
                                   std::to_string(mesh.n_faces()) + " faces, the spline space " +
                                   std::to_string(space.face_count()));
  }
  std::vector<double> scale(mesh.n_faces(), 0.0);
  for (int f : space.domain_faces()) {
    const Eigen::Matrix<double, 3, 2> p = space.atlas().face_positions(space.chart_of(f), f);
    const Eigen::Vector2d a = (p.row(1) - p.row(0)).transpose();
    const Eigen::Vector2d b = (p.row(2) - p.row(0)).transpose();
    const double chart_area = 0.5 * std::abs(ricci::cross2d(a, b));
    Eigen::Vector3d corner[3];
    int k = 0;
    for (auto v : mesh.fv_range(mesh.face_handle(f))) corner[k++] = ricci::to_eigen(mesh.point(v));
    const double area = 0.5 * (corner[1] - corner[0]).cross(corner[2] - corner[0]).norm();
    if (chart_area > 0.0 && area > 0.0)
      scale[static_cast<std::size_t>(f)] = std::sqrt(chart_area / area);
  }
  return scale;
}

}  // namespace spline

#include "ricci/intrinsic/intrinsic_triangulation.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "ricci/mesh/errors.h"
#include "ricci/metric/geometry.h"
#include "ricci/util/edge_key.h"
#include "ricci/util/parallel.h"

namespace ricci {
namespace {

// log(e^a + e^b) without overflow.
double log_sum_exp(double a, double b) {
  const double m = std::max(a, b);
  return m + std::log(std::exp(a - m) + std::exp(b - m));
}

// (b^2 + c^2 - a^2) / (b c) for the face of halfedge h, a its edge: 2 cos of the angle opposite.
double opposite_cosine_twice(const IntrinsicTriangulation& tri, int h, const Eigen::VectorXd& u) {
  const double a = tri.log_length_at(tri.edge[static_cast<size_t>(h)], u);
  const double b =
      tri.log_length_at(tri.edge[static_cast<size_t>(IntrinsicTriangulation::next(h))], u);
  const double c =
      tri.log_length_at(tri.edge[static_cast<size_t>(IntrinsicTriangulation::prev(h))], u);
  return std::exp(b - c) + std::exp(c - b) - std::exp(2.0 * a - b - c);
}

}  // namespace

double IntrinsicTriangulation::log_length_at(int e, const Eigen::VectorXd& u) const {
  const int h = edge_halfedge[static_cast<size_t>(e)];
  return log_length[e] + 0.5 * (u[tail[static_cast<size_t>(h)]] + u[head(h)]);
}

IntrinsicTriangulation make_intrinsic_triangulation(const Mesh& mesh,
                                                    const Eigen::VectorXd& edge_lengths) {
  if (edge_lengths.size() != static_cast<Eigen::Index>(mesh.n_edges())) {
    throw InvalidInputError("intrinsic triangulation: " + std::to_string(edge_lengths.size()) +
                            " edge lengths for " + std::to_string(mesh.n_edges()) + " edges");
  }
  IntrinsicTriangulation tri;
  tri.vertex_count = static_cast<int>(mesh.n_vertices());
  const size_t halfedges = 3 * mesh.n_faces();
  tri.tail.assign(halfedges, -1);
  tri.twin.assign(halfedges, -1);
  tri.edge.assign(halfedges, -1);
  tri.edge_halfedge.assign(mesh.n_edges(), -1);
  tri.log_length.resize(static_cast<Eigen::Index>(mesh.n_edges()));
  std::vector<int> slot_of(mesh.n_halfedges(), -1);
  for (auto f : mesh.faces()) {
    int k = 0;
    for (auto h : mesh.fh_range(f)) {
      if (k == 3)
        throw InvalidInputError("intrinsic triangulation: face " + std::to_string(f.idx()) +
                                " is not a triangle");
      const int slot = 3 * f.idx() + k++;
      slot_of[static_cast<size_t>(h.idx())] = slot;
      tri.tail[static_cast<size_t>(slot)] = mesh.from_vertex_handle(h).idx();
      tri.edge[static_cast<size_t>(slot)] = mesh.edge_handle(h).idx();
      tri.edge_halfedge[static_cast<size_t>(mesh.edge_handle(h).idx())] = slot;
    }
  }
  for (auto h : mesh.halfedges()) {
    const int slot = slot_of[static_cast<size_t>(h.idx())];
    const int opposite = slot_of[static_cast<size_t>(mesh.opposite_halfedge_handle(h).idx())];
    if (slot < 0 || opposite < 0) {
      throw InvalidInputError(
          "intrinsic triangulation: the mesh has a boundary (closed surfaces only)");
    }
    tri.twin[static_cast<size_t>(slot)] = opposite;
  }
  for (auto e : mesh.edges()) {
    const double l = edge_lengths[e.idx()];
    if (!(l > 0) || !std::isfinite(l)) {
      throw InvalidInputError("intrinsic triangulation: edge " + std::to_string(e.idx()) +
                              " has length " + std::to_string(l));
    }
    tri.log_length[e.idx()] = std::log(l);
  }
  return tri;
}

bool is_flippable(const IntrinsicTriangulation& tri, int e) {
  const int h = tri.edge_halfedge[static_cast<size_t>(e)];
  return h / 3 != tri.twin[static_cast<size_t>(h)] / 3;
}

void flip_edge(IntrinsicTriangulation& tri, int e) {
  using T = IntrinsicTriangulation;
  const int h = tri.edge_halfedge[static_cast<size_t>(e)];
  const int t = tri.twin[static_cast<size_t>(h)];
  // Face A = (i, j, k) with h: i->j, ha: j->k, hb: k->i; face B = (j, i, l) with t: j->i,
  // tb1: i->l, tb2: l->j. After the flip A = (l, k, i) in slots (h, ha, hb) and
  // B = (k, l, j) in slots (t, tb1, tb2).
  const int ha = T::next(h), hb = T::prev(h), tb1 = T::next(t), tb2 = T::prev(t);
  const int k = tri.tail[static_cast<size_t>(hb)], l = tri.tail[static_cast<size_t>(tb2)];
  const double ij = tri.log_length[e];
  const double jk = tri.log_length[tri.edge[static_cast<size_t>(ha)]];
  const double ki = tri.log_length[tri.edge[static_cast<size_t>(hb)]];
  const double il = tri.log_length[tri.edge[static_cast<size_t>(tb1)]];
  const double lj = tri.log_length[tri.edge[static_cast<size_t>(tb2)]];
  tri.log_length[e] = log_sum_exp(ki + lj, il + jk) - ij;

  const std::array<int, 4> from = {hb, tb1, tb2, ha};
  const std::array<int, 4> to = {ha, hb, tb1, tb2};
  std::array<int, 4> old_tail{}, old_twin{}, old_edge{};
  for (size_t n = 0; n < 4; ++n) {
    old_tail[n] = tri.tail[static_cast<size_t>(from[n])];
    old_twin[n] = tri.twin[static_cast<size_t>(from[n])];
    old_edge[n] = tri.edge[static_cast<size_t>(from[n])];
  }
  const auto moved = [&](int slot) {
    for (size_t n = 0; n < 4; ++n) {
      if (from[n] == slot) return to[n];
    }
    return slot;
  };
  for (size_t n = 0; n < 4; ++n) {
    const auto s = static_cast<size_t>(to[n]);
    tri.tail[s] = old_tail[n];
    tri.edge[s] = old_edge[n];
    tri.edge_halfedge[static_cast<size_t>(old_edge[n])] = to[n];
  }
  for (size_t n = 0; n < 4; ++n) {
    const int twin = moved(old_twin[n]);
    tri.twin[static_cast<size_t>(to[n])] = twin;
    tri.twin[static_cast<size_t>(twin)] = to[n];
  }
  tri.tail[static_cast<size_t>(h)] = l;
  tri.tail[static_cast<size_t>(t)] = k;
  tri.twin[static_cast<size_t>(h)] = t;
  tri.twin[static_cast<size_t>(t)] = h;
  tri.edge_halfedge[static_cast<size_t>(e)] = h;
}

double delaunay_measure(const IntrinsicTriangulation& tri, int e, const Eigen::VectorXd& u) {
  const int h = tri.edge_halfedge[static_cast<size_t>(e)];
  return opposite_cosine_twice(tri, h, u) +
         opposite_cosine_twice(tri, tri.twin[static_cast<size_t>(h)], u);
}

DelaunayFlipResult flip_to_delaunay(IntrinsicTriangulation& tri, const Eigen::VectorXd& u,
                                    double margin, double max_flips_per_edge,
                                    std::vector<int>* flip_log) {
  DelaunayFlipResult result;
  const int edges = tri.edge_count();
  const auto wants_flip = [&](int e) {
    return is_flippable(tri, e) && delaunay_measure(tri, e, u) < -margin;
  };
  // Every edge's test on the triangulation as given, edge-parallel (it only reads). An edge
  // reads its two faces alone, which change only when it or an edge of theirs flips (touched):
  // an untouched edge's test at its turn is this one, so the flips are Lawson's serial
  // sequence, the same on any number of threads.
  std::vector<char> flips_first(static_cast<size_t>(edges)), touched(static_cast<size_t>(edges), 0);
  parallel_for(static_cast<size_t>(edges), 0, [&](size_t e) {
    flips_first[e] = wants_flip(static_cast<int>(e)) ? 1 : 0;
  });
  std::vector<int> stack(static_cast<size_t>(edges));
  std::vector<char> queued(static_cast<size_t>(edges), 1);
  for (int e = 0; e < edges; ++e) stack[static_cast<size_t>(e)] = e;
  const double budget = max_flips_per_edge * edges;
  while (!stack.empty()) {
    const int e = stack.back();
    stack.pop_back();
    queued[static_cast<size_t>(e)] = 0;
    if (!(touched[static_cast<size_t>(e)] ? wants_flip(e) : flips_first[static_cast<size_t>(e)])) {
      continue;
    }
    if (result.flips >= budget) return result;
    flip_edge(tri, e);
    ++result.flips;
    if (flip_log) flip_log->push_back(e);
    touched[static_cast<size_t>(e)] = 1;
    const int h = tri.edge_halfedge[static_cast<size_t>(e)];
    const int t = tri.twin[static_cast<size_t>(h)];
    for (int s : {IntrinsicTriangulation::next(h), IntrinsicTriangulation::prev(h),
                  IntrinsicTriangulation::next(t), IntrinsicTriangulation::prev(t)}) {
      const int f = tri.edge[static_cast<size_t>(s)];
      touched[static_cast<size_t>(f)] = 1;
      if (!queued[static_cast<size_t>(f)]) {
        queued[static_cast<size_t>(f)] = 1;
        stack.push_back(f);
      }
    }
  }
  result.delaunay = true;
  return result;
}

bool intrinsic_corner_angles(const IntrinsicTriangulation& tri, const Eigen::VectorXd& u,
                             Eigen::MatrixX3d& angles, Eigen::MatrixX3d* cotangents) {
  const int faces = tri.face_count();
  angles.resize(faces, 3);
  if (cotangents) cotangents->resize(faces, 3);
  std::atomic<bool> valid{true};
  // Each face writes its own rows: the same result on any number of threads.
  parallel_for(static_cast<std::size_t>(faces), 0, [&](std::size_t face) {
    const int f = static_cast<int>(face);
    // l[k] is opposite corner k, the tail of halfedge 3f + k: the edge of halfedge 3f + k + 1.
    double log_l[3];
    for (int k = 0; k < 3; ++k)
      log_l[k] = tri.log_length_at(tri.edge[static_cast<size_t>(3 * f + (k + 1) % 3)], u);
    const double scale = std::max({log_l[0], log_l[1], log_l[2]});
    const double l[3] = {std::exp(log_l[0] - scale), std::exp(log_l[1] - scale),
                         std::exp(log_l[2] - scale)};
    double theta[3], cosine[3], sine[3];
    if (!triangle_angles(Geometry::euclidean, l, theta, cosine, sine)) {
      valid.store(false, std::memory_order_relaxed);
      return;
    }
    for (int k = 0; k < 3; ++k) {
      angles(f, k) = theta[k];
      if (cotangents) (*cotangents)(f, k) = cosine[k] / sine[k];
    }
  });
  return valid.load();
}

Eigen::VectorXd intrinsic_curvature(const IntrinsicTriangulation& tri,
                                    const Eigen::MatrixX3d& angles) {
  Eigen::VectorXd curvature = Eigen::VectorXd::Constant(tri.vertex_count, 2.0 * M_PI);
  for (int f = 0; f < tri.face_count(); ++f) {
    for (int k = 0; k < 3; ++k) curvature[tri.tail[static_cast<size_t>(3 * f + k)]] -= angles(f, k);
  }
  return curvature;
}

int euler_characteristic(const IntrinsicTriangulation& tri) {
  return tri.vertex_count - tri.edge_count() + tri.face_count();
}

bool is_simplicial(const IntrinsicTriangulation& tri) {
  // Each edge's ends, smaller first, as one sortable key; a repeated key is a double edge.
  std::vector<std::uint64_t> pairs;
  pairs.reserve(static_cast<size_t>(tri.edge_count()));
  for (int e = 0; e < tri.edge_count(); ++e) {
    const int h = tri.edge_halfedge[static_cast<size_t>(e)];
    const int a = tri.tail[static_cast<size_t>(h)], b = tri.head(h);
    if (a == b) return false;
    pairs.push_back(undirected_edge_key(a, b));
  }
  std::sort(pairs.begin(), pairs.end());
  return std::adjacent_find(pairs.begin(), pairs.end()) == pairs.end();
}

IntrinsicMesh to_mesh(const IntrinsicTriangulation& tri, const Eigen::VectorXd& u,
                      const Eigen::MatrixX3d& positions) {
  if (positions.rows() != tri.vertex_count || u.size() != tri.vertex_count) {
    throw InvalidInputError(
        "intrinsic triangulation: positions or scale factors do not match its " +
        std::to_string(tri.vertex_count) + " vertices");
  }
  const MeshTables tables = to_mesh_tables(tri);
  IntrinsicMesh out;
  std::vector<int> edge_of;
  out.mesh = mesh_of_tables(tables, positions, edge_of);
  out.lengths = by_mesh_edge(table_edge_lengths(tri, tables, u), edge_of);
  return out;
}

namespace {

// OpenMesh's add_face gives a face its last halfedge (from the face's last vertex to its
// first): the face's halfedges, as build_mesh_tables walks them, start at 3f + this.
constexpr int kFirstHalfedge = 2;

// Table edge of each of the triangulation's edges: numbered in the order to_mesh's add_face
// calls meet them (face by face, halfedges 3f, 3f+1, 3f+2).
std::vector<int> table_edge_numbers(const IntrinsicTriangulation& tri) {
  std::vector<int> number(static_cast<size_t>(tri.edge_count()), -1);
  int next = 0;
  for (size_t h = 0; h < tri.tail.size(); ++h) {
    int& n = number[static_cast<size_t>(tri.edge[h])];
    if (n < 0) n = next++;
  }
  return number;
}

}  // namespace

MeshTables to_mesh_tables(const IntrinsicTriangulation& tri) {
  if (!is_simplicial(tri)) {
    throw TopologyError(
        "intrinsic triangulation: a loop or a double edge, not a simplicial complex");
  }
  const std::vector<int> number = table_edge_numbers(tri);
  MeshTables t;
  const int faces = tri.face_count();
  t.face_vertices.resize(faces, 3);
  t.face_edges.resize(faces, 3);
  t.edge_vertices.resize(tri.edge_count(), 2);
  t.valence = Eigen::VectorXi::Zero(tri.vertex_count);
  for (int f = 0; f < faces; ++f) {
    for (int k = 0; k < 3; ++k) {
      // The face's k-th halfedge as the mesh walks it runs from its k-th vertex to the next
      // and is opposite the vertex k + 2.
      const int h = 3 * f + (k + kFirstHalfedge) % 3;
      t.face_vertices(f, k) = tri.tail[static_cast<size_t>(h)];
      t.face_edges(f, (k + 2) % 3) = number[static_cast<size_t>(tri.edge[static_cast<size_t>(h)])];
      ++t.valence[tri.tail[static_cast<size_t>(h)]];
    }
  }
  std::vector<char> seen(static_cast<size_t>(tri.edge_count()), 0);
  for (size_t h = 0; h < tri.tail.size(); ++h) {
    const int e = number[static_cast<size_t>(tri.edge[h])];
    if (seen[static_cast<size_t>(e)]) continue;
    seen[static_cast<size_t>(e)] = 1;  // its first halfedge, as the mesh's new_edge made it
    t.edge_vertices(e, 0) = tri.tail[h];
    t.edge_vertices(e, 1) = tri.head(static_cast<int>(h));
  }
  for (int v = 0; v < tri.vertex_count; ++v) {
    if (t.valence[v] == 0) {
      throw TopologyError("vertex " + std::to_string(v) + " is isolated (in no face)");
    }
  }
  t.is_boundary_vertex.assign(static_cast<size_t>(tri.vertex_count), 0);
  t.euler_characteristic = euler_characteristic(tri);
  return t;
}

Eigen::VectorXd table_edge_lengths(const IntrinsicTriangulation& tri, const MeshTables& tables,
                                   const Eigen::VectorXd& u) {
  if (tables.num_edges() != tri.edge_count() || u.size() != tri.vertex_count) {
    throw InvalidInputError("intrinsic triangulation: tables or scale factors do not match it");
  }
  const std::vector<int> number = table_edge_numbers(tri);
  Eigen::VectorXd lengths(tri.edge_count());
  for (int e = 0; e < tri.edge_count(); ++e) {
    lengths[number[static_cast<size_t>(e)]] = std::exp(tri.log_length_at(e, u));
  }
  return lengths;
}

Mesh mesh_of_tables(const MeshTables& tables, const Eigen::MatrixX3d& positions,
                    std::vector<int>& edge_of) {
  if (positions.rows() != tables.num_vertices()) {
    throw InvalidInputError("mesh of tables: the positions do not match its " +
                            std::to_string(tables.num_vertices()) + " vertices");
  }
  Mesh mesh;
  const auto vertices = static_cast<size_t>(tables.num_vertices());
  const auto faces = static_cast<size_t>(tables.num_faces());
  mesh.reserve(vertices, static_cast<size_t>(tables.num_edges()), faces);
  for (int v = 0; v < tables.num_vertices(); ++v) {
    mesh.add_vertex(to_openmesh(positions.row(v).transpose()));
  }
  edge_of.assign(static_cast<size_t>(tables.num_edges()), -1);
  for (int f = 0; f < tables.num_faces(); ++f) {
    // In the triangulation's corner order (to_mesh's), which the tables rotated.
    VertexHandle corner[3];
    for (int k = 0; k < 3; ++k) {
      corner[(k + kFirstHalfedge) % 3] =
          mesh.vertex_handle(static_cast<unsigned>(tables.face_vertices(f, k)));
    }
    const FaceHandle face = mesh.add_face(corner[0], corner[1], corner[2]);
    if (!face.is_valid()) {
      throw TopologyError("mesh of tables: face " + std::to_string(f) + " is not manifold");
    }
    // The face's halfedge from its corner k to the next is the table edge opposite corner k + 2.
    for (const HalfedgeHandle h : mesh.fh_range(face)) {
      const int from = mesh.from_vertex_handle(h).idx();
      const int k = from == tables.face_vertices(f, 0) ? 0 : from == tables.face_vertices(f, 1) ? 1 : 2;
      edge_of[static_cast<size_t>(tables.face_edges(f, (k + 2) % 3))] = mesh.edge_handle(h).idx();
    }
  }
  return mesh;
}

namespace {

bool is_identity(const std::vector<int>& edge_of) {
  for (size_t e = 0; e < edge_of.size(); ++e) {
    if (edge_of[e] != static_cast<int>(e)) return false;
  }
  return true;
}

}  // namespace

Eigen::VectorXd by_mesh_edge(Eigen::VectorXd by_table_edge, const std::vector<int>& edge_of) {
  if (by_table_edge.size() == 0) return by_table_edge;
  if (static_cast<size_t>(by_table_edge.size()) != edge_of.size()) {
    throw InvalidInputError("by_mesh_edge: values and edge map differ in size");
  }
  if (is_identity(edge_of)) return by_table_edge;  // to_mesh_tables' tables: no move
  Eigen::VectorXd out(by_table_edge.size());
  for (size_t e = 0; e < edge_of.size(); ++e) {
    out[edge_of[e]] = by_table_edge[static_cast<Eigen::Index>(e)];
  }
  return out;
}

}  // namespace ricci

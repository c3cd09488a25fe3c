#include "ricci/topology/cut_graph.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <queue>
#include <string>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/topology_util.h"

namespace ricci {
namespace {

/// The quotient surface where each boundary loop is one node: node(v) = v for interior vertices,
/// n_vertices + loop index for boundary vertices.
struct Quotient {
  int vertex_count = 0;
  std::vector<int> loop_of_vertex;
  std::vector<std::vector<VertexHandle>> loop_vertices;

  int node(VertexHandle v) const {
    const int loop = loop_of_vertex[v.idx()];
    return loop < 0 ? v.idx() : vertex_count + loop;
  }
  int node_count() const { return vertex_count + static_cast<int>(loop_vertices.size()); }
};

/// Shortest-path tree of the quotient from the root's node over interior edges.
struct ShortestPathTree {
  std::vector<double> distance;        // by node
  std::vector<HalfedgeHandle> parent;  // by node: halfedge arriving at the node
  std::vector<char> edge_in_tree;      // by edge
};

ShortestPathTree shortest_path_tree(const Mesh& mesh, const Quotient& q, int root_node,
                                    const Eigen::VectorXd& lengths,
                                    bool over_boundary_edges = false) {
  const int n = q.node_count();
  ShortestPathTree t;
  t.distance.assign(n, std::numeric_limits<double>::infinity());
  t.parent.assign(n, HalfedgeHandle());
  t.edge_in_tree.assign(mesh.n_edges(), 0);
  std::vector<char> done(n, 0);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
  t.distance[root_node] = 0.0;
  heap.push({0.0, root_node});
  auto relax_from = [&](int node, VertexHandle v) {
    for (auto h : mesh.voh_range(v)) {
      if (!over_boundary_edges && mesh.is_boundary(mesh.edge_handle(h))) continue;
      const int m = q.node(mesh.to_vertex_handle(h));
      if (m == node || done[m]) continue;
      const double d = t.distance[node] + lengths[mesh.edge_handle(h).idx()];
      if (d < t.distance[m]) {
        t.distance[m] = d;
        t.parent[m] = h;
        heap.push({d, m});
      }
    }
  };
  while (!heap.empty()) {
    const auto [d, node] = heap.top();
    heap.pop();
    if (done[node] || d > t.distance[node]) continue;
    done[node] = 1;
    if (node < q.vertex_count) {
      relax_from(node, VertexHandle(node));
    } else {
      for (auto v : q.loop_vertices[node - q.vertex_count]) relax_from(node, v);
    }
  }
  for (int node = 0; node < n; ++node) {
    const bool used = node >= q.vertex_count || q.loop_of_vertex[node] < 0;
    if (!used) continue;
    if (!done[node]) {
      const std::string what = node < q.vertex_count
                                   ? "vertex " + std::to_string(node)
                                   : "boundary loop " + std::to_string(node - q.vertex_count);
      throw TopologyError("cut graph: " + what + " is not connected to the root");
    }
    if (t.parent[node].is_valid()) t.edge_in_tree[mesh.edge_handle(t.parent[node]).idx()] = 1;
  }
  return t;
}

/// Halfedges from the root's node down the tree to `node`.
std::vector<HalfedgeHandle> tree_path(const Mesh& mesh, const Quotient& q,
                                      const ShortestPathTree& t, int node) {
  std::vector<HalfedgeHandle> path;
  while (t.parent[node].is_valid()) {
    path.push_back(t.parent[node]);
    node = q.node(mesh.from_vertex_handle(t.parent[node]));
  }
  std::reverse(path.begin(), path.end());
  return path;
}

double path_length(const Mesh& mesh, const std::vector<HalfedgeHandle>& path,
                   const Eigen::VectorXd& lengths) {
  double sum = 0.0;
  for (auto h : path) sum += lengths[mesh.edge_handle(h).idx()];
  return sum;
}

/// Cotree edges: maximum spanning tree of the dual graph over interior non-tree edges, weighted
/// by the length of the loop each closes (Erickson-Whittlesey). Returns the leftover edges.
std::vector<EdgeHandle> cotree_leftovers(const Mesh& mesh, const Quotient& q,
                                         const ShortestPathTree& t,
                                         const Eigen::VectorXd& lengths) {
  std::vector<std::pair<double, int>> candidates;
  for (auto e : mesh.edges()) {
    if (mesh.is_boundary(e) || t.edge_in_tree[e.idx()]) continue;
    const auto h = mesh.halfedge_handle(e, 0);
    const double w = t.distance[q.node(mesh.from_vertex_handle(h))] + lengths[e.idx()] +
                     t.distance[q.node(mesh.to_vertex_handle(h))];
    candidates.push_back({w, e.idx()});
  }
  // Ties broken by edge index so the result does not depend on the sort's stability.
  std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  });
  detail::DisjointSets dual(mesh.n_faces());
  std::vector<EdgeHandle> leftovers;
  for (const auto& [w, index] : candidates) {
    const EdgeHandle e(index);
    const int f0 = mesh.face_handle(mesh.halfedge_handle(e, 0)).idx();
    const int f1 = mesh.face_handle(mesh.halfedge_handle(e, 1)).idx();
    if (!dual.unite(f0, f1)) leftovers.push_back(e);
  }
  return leftovers;
}

/// The quotient for the given boundary loops. \throw TopologyError on a vertex met twice.
Quotient make_quotient(const Mesh& mesh, const std::vector<std::vector<HalfedgeHandle>>& loops) {
  Quotient q;
  q.vertex_count = static_cast<int>(mesh.n_vertices());
  q.loop_of_vertex.assign(mesh.n_vertices(), -1);
  for (int j = 0; j < static_cast<int>(loops.size()); ++j) {
    std::vector<VertexHandle> vertices;
    for (auto h : loops[j]) {
      const auto v = mesh.to_vertex_handle(h);
      if (q.loop_of_vertex[v.idx()] >= 0) {
        throw TopologyError("cut graph: vertex " + std::to_string(v.idx()) +
                            " lies on the boundary twice (non-manifold)");
      }
      q.loop_of_vertex[v.idx()] = j;
      vertices.push_back(v);
    }
    q.loop_vertices.push_back(std::move(vertices));
  }
  return q;
}

/// Loop closed by leftover edge e: tree path to from(h), h, tree path back from to(h).
CutPath make_loop(const Mesh& mesh, const Quotient& q, const ShortestPathTree& tree, EdgeHandle e,
                  const Eigen::VectorXd& lengths) {
  CutPath loop;
  loop.kind = CutPathKind::homology_loop;
  loop.generator = mesh.halfedge_handle(e, 0);
  loop.halfedges = tree_path(mesh, q, tree, q.node(mesh.from_vertex_handle(loop.generator)));
  loop.halfedges.push_back(loop.generator);
  const auto back = tree_path(mesh, q, tree, q.node(mesh.to_vertex_handle(loop.generator)));
  for (auto it = back.rbegin(); it != back.rend(); ++it) {
    loop.halfedges.push_back(mesh.opposite_halfedge_handle(*it));
  }
  loop.length = path_length(mesh, loop.halfedges, lengths);
  return loop;
}

void check_path_continuity(const Mesh& mesh, const CutGraph& g, const CutPath& path) {
  for (size_t k = 0; k + 1 < path.halfedges.size(); ++k) {
    const auto a = mesh.to_vertex_handle(path.halfedges[k]);
    const auto b = mesh.from_vertex_handle(path.halfedges[k + 1]);
    const int la = g.boundary_loop_of_vertex[a.idx()];
    if (a != b && (la < 0 || la != g.boundary_loop_of_vertex[b.idx()])) {
      throw TopologyError("cut graph: path breaks between vertices " + std::to_string(a.idx()) +
                          " and " + std::to_string(b.idx()));
    }
  }
}

}  // namespace

Eigen::VectorXd checked_edge_lengths(const Mesh& mesh, const Eigen::VectorXd& edge_lengths) {
  if (edge_lengths.size() == 0) {
    Eigen::VectorXd lengths(mesh.n_edges());
    for (auto e : mesh.edges()) lengths[e.idx()] = mesh.calc_edge_length(e);
    return checked_edge_lengths(mesh, lengths);
  }
  if (edge_lengths.size() != static_cast<Eigen::Index>(mesh.n_edges())) {
    throw InvalidInputError("edge lengths: " + std::to_string(edge_lengths.size()) +
                            " values for " + std::to_string(mesh.n_edges()) + " edges");
  }
  for (Eigen::Index i = 0; i < edge_lengths.size(); ++i) {
    if (!std::isfinite(edge_lengths[i]) || edge_lengths[i] <= 0.0) {
      throw InvalidInputError("edge lengths: edge " + std::to_string(i) +
                              " has non-positive or non-finite length");
    }
  }
  return edge_lengths;
}

VertexHandle central_vertex(const Mesh& mesh, const Eigen::VectorXd& edge_lengths, int samples) {
  if (mesh.n_vertices() == 0) throw InvalidInputError("central vertex: mesh has no vertices");
  const Eigen::VectorXd lengths = checked_edge_lengths(mesh, edge_lengths);
  // Distances over every edge, no boundary loop contracted.
  const Quotient q = make_quotient(mesh, {});
  const auto distances = [&](int from) {
    return shortest_path_tree(mesh, q, from, lengths, true).distance;
  };
  const auto farthest = [](const std::vector<double>& d) {
    return static_cast<int>(std::max_element(d.begin(), d.end()) - d.begin());
  };
  std::vector<double> eccentricity(mesh.n_vertices(), 0.0);
  std::vector<double> to_samples = distances(0);  // distance to the nearest sample so far
  int sample = farthest(to_samples);
  for (int k = 0; k < std::max(samples, 1); ++k) {
    const std::vector<double> d = distances(sample);
    for (size_t v = 0; v < d.size(); ++v) {
      eccentricity[v] = std::max(eccentricity[v], d[v]);
      to_samples[v] = k == 0 ? d[v] : std::min(to_samples[v], d[v]);
    }
    sample = farthest(to_samples);
  }
  const auto centre = std::min_element(eccentricity.begin(), eccentricity.end());
  return VertexHandle(static_cast<int>(centre - eccentricity.begin()));
}

std::vector<VertexHandle> spread_vertices(const Mesh& mesh, VertexHandle first,
                                          const Eigen::VectorXd& edge_lengths, int count) {
  if (!first.is_valid() || first.idx() >= static_cast<int>(mesh.n_vertices())) {
    throw InvalidInputError("spread vertices: vertex " + std::to_string(first.idx()) +
                            " is out of range");
  }
  const Eigen::VectorXd lengths = checked_edge_lengths(mesh, edge_lengths);
  const Quotient q = make_quotient(mesh, {});
  std::vector<VertexHandle> samples{first};
  std::vector<double> to_samples = shortest_path_tree(mesh, q, first.idx(), lengths, true).distance;
  while (static_cast<int>(samples.size()) < count) {
    const auto far = std::max_element(to_samples.begin(), to_samples.end());
    if (!(*far > 0.0)) break;  // every vertex is a sample already
    samples.emplace_back(static_cast<int>(far - to_samples.begin()));
    const std::vector<double> d =
        shortest_path_tree(mesh, q, samples.back().idx(), lengths, true).distance;
    for (size_t v = 0; v < d.size(); ++v) to_samples[v] = std::min(to_samples[v], d[v]);
  }
  return samples;
}

CutGraph compute_cut_graph(const Mesh& mesh, VertexHandle root, const Eigen::VectorXd& edge_lengths,
                           const CutGraphOptions& options) {
  if (!root.is_valid() || root.idx() >= static_cast<int>(mesh.n_vertices())) {
    throw InvalidInputError("cut graph: root vertex " + std::to_string(root.idx()) +
                            " is out of range");
  }
  if (mesh.n_faces() == 0) throw InvalidInputError("cut graph: mesh has no faces");
  const Eigen::VectorXd lengths = checked_edge_lengths(mesh, edge_lengths);

  CutGraph g;
  g.root = root;
  g.boundary_loops = find_boundary_loops(mesh);
  g.boundary_loop_count = static_cast<int>(g.boundary_loops.size());
  g.euler_characteristic = euler_characteristic(mesh);
  const int twice_genus = 2 - g.euler_characteristic - g.boundary_loop_count;
  if (twice_genus < 0 || twice_genus % 2 != 0) {
    throw TopologyError("cut graph: Euler characteristic " +
                        std::to_string(g.euler_characteristic) + " with " +
                        std::to_string(g.boundary_loop_count) +
                        " boundary loops is not a connected orientable surface");
  }
  g.genus = twice_genus / 2;

  const Quotient q = make_quotient(mesh, g.boundary_loops);
  g.boundary_loop_of_vertex = q.loop_of_vertex;

  const int root_node = q.node(root);
  const ShortestPathTree tree = shortest_path_tree(mesh, q, root_node, lengths);
  const std::vector<EdgeHandle> leftovers = cotree_leftovers(mesh, q, tree, lengths);
  if (static_cast<int>(leftovers.size()) != twice_genus) {
    throw TopologyError("cut graph: " + std::to_string(leftovers.size()) +
                        " leftover edges where 2g = " + std::to_string(twice_genus) +
                        " (faces not connected across interior edges?)");
  }

  g.is_cut_edge.assign(mesh.n_edges(), 0);
  for (auto e : leftovers) g.loops.push_back(make_loop(mesh, q, tree, e, lengths));
  for (int j = 0; j < g.boundary_loop_count; ++j) {
    const int node = q.vertex_count + j;
    if (node == root_node) continue;
    CutPath connector;
    connector.kind = CutPathKind::boundary_connector;
    connector.boundary_loop = j;
    connector.halfedges = tree_path(mesh, q, tree, node);
    connector.length = path_length(mesh, connector.halfedges, lengths);
    g.boundary_connectors.push_back(std::move(connector));
  }
  for (const auto* paths : {&g.loops, &g.boundary_connectors}) {
    for (const auto& path : *paths) {
      if (options.check_paths) check_path_continuity(mesh, g, path);
      for (auto h : path.halfedges) g.is_cut_edge[mesh.edge_handle(h).idx()] = 1;
    }
  }
  return g;
}

}  // namespace ricci

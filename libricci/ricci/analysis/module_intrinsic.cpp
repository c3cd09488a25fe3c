// The circle domain's flat metric by the conformal flow with intrinsic Delaunay flips, for
// meshes where the fixed-connectivity flow breaks triangles (a conformal factor that varies by
// e^10 over lion.off). The flow runs on the double cover (two copies glued along the boundary,
// each boundary vertex's target doubled), whose solution is symmetric under the reflection that
// swaps the copies, so every boundary loop is the fixed set of that reflection. The flipped
// triangulation may cross a loop, but only by an edge joining a vertex to its own mirror image,
// in two faces that each hold one boundary vertex (the reflection maps the Delaunay
// triangulation onto itself and two edges cannot cross): the half of the double covering the
// mesh is then the faces free of mirror vertices plus, of each crossing face, the right triangle
// on the mesh's side of the loop, whose new corner is the crossing edge's midpoint on the loop.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <queue>

#include "ricci/analysis/module_internal.h"
#include "ricci/intrinsic/conformal_flow.h"
#include "ricci/mesh/errors.h"
#include "ricci/topology/double_cover.h"

namespace ricci::detail {

namespace {

/// A face of the half: corners (indices into the layout), side k from corner k to k + 1 with
/// its length and the key of the side it shares with a neighbour (-1: none).
struct HalfFace {
  std::array<int, 3> corner{};
  std::array<double, 3> length{};
  std::array<long, 3> key{};
};

class IntrinsicFlatMetric : public FlatMetric {
 public:
  IntrinsicFlatMetric(const Mesh& mesh, const MeshTables& tables, const FlowOptions& options)
      : mesh_(mesh), tables_(tables), cover_(double_cover(mesh)) {
    if (cover_.split_edges > 0) {
      throw InvalidInputError(
          "the intrinsic circle domain needs a mesh without interior edges between boundary "
          "vertices");
    }
    settings_.tolerance = options.tolerance;
    settings_.solver = options.solver;
    tri_ = make_intrinsic_triangulation(cover_.mesh, mesh_edge_lengths(cover_.mesh));
    const int n = tables.num_vertices();
    const int doubled = static_cast<int>(cover_.mesh.n_vertices());
    side_.assign(doubled, -1);
    mirror_.assign(doubled, -1);
    for (int v = 0; v < n; ++v) {
      side_[v] = tables.is_boundary_vertex[v] ? 0 : 1;
      mirror_[v] = cover_.mirror_vertex[v];
      mirror_[cover_.mirror_vertex[v]] = v;
    }
    loop_next_.assign(n, -1);
    for (const std::vector<int>& loop : tables.boundary_loops) {
      for (size_t i = 0; i < loop.size(); ++i) loop_next_[loop[i]] = loop[(i + 1) % loop.size()];
    }
  }

  FlowResult solve(const Targets& targets) override {
    const int doubled = static_cast<int>(cover_.mesh.n_vertices());
    Eigen::VectorXd target(doubled);
    for (int v = 0; v < doubled; ++v) {
      const int original = cover_.to_original_vertex[v];
      target[v] = (side_[v] == 0 ? 2.0 : 1.0) * targets.curvature[original];
    }
    IntrinsicFlowResult r = intrinsic_conformal_flow(tri_, target, settings_);
    tri_ = std::move(r.triangulation);
    for (int e = 0; e < tri_.edge_count(); ++e) tri_.log_length[e] = tri_.log_length_at(e, r.u);
    r.triangulation = IntrinsicTriangulation{};
    FlowResult figures = to_flow_result(r);
    if (figures.converged() || r.max_error < settings_.freeze_connectivity_below) build_half();
    solved_ = true;
    return figures;
  }

  std::vector<double> loop_lengths(const std::vector<int>& loop) const override {
    std::vector<double> edge(loop.size());
    for (size_t i = 0; i < loop.size(); ++i) {
      const int x = loop[i], y = loop[(i + 1) % loop.size()];
      if (!solved_) {
        edge[i] =
            (mesh_.point(mesh_.vertex_handle(x)) - mesh_.point(mesh_.vertex_handle(y))).norm();
        continue;
      }
      const auto direct = rim_.find({std::min(x, y), std::max(x, y)});
      if (direct != rim_.end()) {
        edge[i] = direct->second;
        continue;
      }
      edge[i] = -1;
      for (const auto& [m, a] : rim_midpoints_[x]) {
        for (const auto& [m2, b] : rim_midpoints_[y]) {
          if (m == m2) edge[i] = a + b;
        }
      }
      if (edge[i] < 0) {
        throw SolverError("the intrinsic triangulation lost the boundary segment " +
                          std::to_string(x) + "-" + std::to_string(y));
      }
    }
    return edge;
  }

  void layout(std::vector<Complex>& z) const override { z = positions_; }

  Eigen::MatrixX3i faces() const override {
    Eigen::MatrixX3i faces(static_cast<Eigen::Index>(half_.size()), 3);
    for (size_t f = 0; f < half_.size(); ++f) {
      for (int k = 0; k < 3; ++k) faces(static_cast<Eigen::Index>(f), k) = half_[f].corner[k];
    }
    return faces;
  }

 private:
  [[nodiscard]] double length(int h) const { return std::exp(tri_.log_length[tri_.edge[h]]); }

  /// The edge of halfedge h runs along a loop: its ends follow each other on the loop and the
  /// faces on its two sides are mirror images.
  [[nodiscard]] bool along_loop(int h) const {
    const int x = tri_.tail[h], y = tri_.head(h);
    if (side_[x] != 0 || side_[y] != 0) return false;
    if (loop_next_[x] != y && loop_next_[y] != x) return false;
    const int t = tri_.twin[h];
    return mirror_[tri_.tail[IntrinsicTriangulation::prev(h)]] ==
           tri_.tail[IntrinsicTriangulation::prev(t)];
  }

  /// The half of the double on the mesh's side (see the file comment), laid out.
  void build_half() {
    const int n = tables_.num_vertices();
    const int faces = tri_.face_count();
    const long edges = tri_.edge_count();
    half_.clear();
    std::vector<int> midpoint(static_cast<size_t>(edges), -1);
    int next_vertex = n;
    // Faces free of mirror vertices, flooded from those with an interior vertex of the mesh
    // across edges that do not run along a loop.
    std::vector<char> kept(static_cast<size_t>(faces), 0);
    std::queue<int> queue;
    const auto has = [&](int f, int s) {
      for (int k = 0; k < 3; ++k) {
        if (side_[tri_.tail[3 * f + k]] == s) return true;
      }
      return false;
    };
    for (int f = 0; f < faces; ++f) {
      if (has(f, 1) && !has(f, -1)) {
        kept[f] = 1;
        queue.push(f);
      }
    }
    while (!queue.empty()) {
      const int f = queue.front();
      queue.pop();
      for (int h = 3 * f; h < 3 * f + 3; ++h) {
        const int g = tri_.twin[h] / 3;
        if (kept[g] || has(g, -1) || along_loop(h)) continue;
        kept[g] = 1;
        queue.push(g);
      }
    }
    for (int f = 0; f < faces; ++f) {
      if (kept[f]) {
        HalfFace face;
        for (int k = 0; k < 3; ++k) {
          const int h = 3 * f + k;
          face.corner[k] = tri_.tail[h];
          face.length[k] = length(h);
          face.key[k] = tri_.edge[h];
        }
        half_.push_back(face);
      } else if (has(f, 1) && has(f, -1)) {
        half_.push_back(crossing_part(f, midpoint, next_vertex));
      }
    }
    lay_out(next_vertex);
    // The loops' pieces: sides of the half without a neighbour.
    std::map<long, int> uses;
    for (const HalfFace& face : half_) {
      for (long key : face.key) {
        if (key >= 0) ++uses[key];
      }
    }
    rim_.clear();
    rim_midpoints_.assign(n, {});
    for (const HalfFace& face : half_) {
      for (int k = 0; k < 3; ++k) {
        if (face.key[k] >= 0 && uses[face.key[k]] > 1) continue;
        const int a = face.corner[k], b = face.corner[(k + 1) % 3];
        if (a < n && b < n) {
          rim_[{std::min(a, b), std::max(a, b)}] = face.length[k];
        } else if (a < n) {
          rim_midpoints_[a].push_back({b, face.length[k]});
        } else if (b < n) {
          rim_midpoints_[b].push_back({a, face.length[k]});
        }
      }
    }
  }

  /// The mesh's side of crossing face f (a loop vertex x and a vertex w with its mirror w'):
  /// the right triangle x, w, m with m the midpoint of w w' on the loop.
  HalfFace crossing_part(int f, std::vector<int>& midpoint, int& next_vertex) const {
    int k = 0;
    while (k < 3 && side_[tri_.tail[3 * f + k]] != 0) ++k;
    const int hx = 3 * f + k;  // x -> p
    const int hp = IntrinsicTriangulation::next(hx), hq = IntrinsicTriangulation::next(hp);
    const int p = tri_.tail[hp], q = tri_.tail[hq];
    if (k == 3 || mirror_[p] != q) {
      throw SolverError(
          "the intrinsic triangulation crosses a boundary loop other than by an "
          "edge between mirror vertices");
    }
    const int e = tri_.edge[hp];
    if (midpoint[e] < 0) midpoint[e] = next_vertex++;
    const int m = midpoint[e];
    const long half_key = static_cast<long>(tri_.edge_count()) + e;
    const double half_edge = 0.5 * length(hp);
    const double slant = 0.5 * (length(hx) + length(hq));
    const double foot = std::sqrt(std::max(0.0, slant * slant - half_edge * half_edge));
    HalfFace face;
    if (side_[p] == 1) {  // x, p, m
      face.corner = {tri_.tail[hx], p, m};
      face.length = {length(hx), half_edge, foot};
      face.key = {tri_.edge[hx], half_key, -1};
    } else {  // x, m, q
      face.corner = {tri_.tail[hx], m, q};
      face.length = {foot, half_edge, length(hq)};
      face.key = {-1, half_key, tri_.edge[hq]};
    }
    return face;
  }

  /// Positions by corner, face by face across shared sides from the first face.
  void lay_out(int vertex_count) {
    positions_.assign(static_cast<size_t>(vertex_count), Complex(0));
    std::vector<char> placed(static_cast<size_t>(vertex_count), 0), done(half_.size(), 0);
    std::map<long, std::vector<int>> by_key;
    for (size_t f = 0; f < half_.size(); ++f) {
      for (long key : half_[f].key) {
        if (key >= 0) by_key[key].push_back(static_cast<int>(f));
      }
    }
    // Corner c of a face whose side from a to b is placed: by the angle at a.
    const auto place = [&](const HalfFace& face, int side) {
      const int a = face.corner[side], b = face.corner[(side + 1) % 3];
      const int c = face.corner[(side + 2) % 3];
      if (placed[c]) return;
      const double ab = face.length[side], bc = face.length[(side + 1) % 3];
      const double ca = face.length[(side + 2) % 3];
      const double cosine = std::clamp((ab * ab + ca * ca - bc * bc) / (2 * ab * ca), -1.0, 1.0);
      const Complex direction =
          (positions_[b] - positions_[a]) / std::abs(positions_[b] - positions_[a]);
      positions_[c] = positions_[a] + ca * direction * std::polar(1.0, std::acos(cosine));
      placed[c] = 1;
    };
    if (half_.empty()) throw SolverError("the intrinsic triangulation has no face on the mesh");
    const HalfFace& first = half_[0];
    positions_[first.corner[0]] = 0;
    positions_[first.corner[1]] = first.length[0];
    placed[first.corner[0]] = placed[first.corner[1]] = 1;
    place(first, 0);
    std::queue<int> queue;
    queue.push(0);
    done[0] = 1;
    while (!queue.empty()) {
      const int f = queue.front();
      queue.pop();
      for (long key : half_[f].key) {
        if (key < 0) continue;
        for (int g : by_key[key]) {
          if (done[g]) continue;
          done[g] = 1;
          const HalfFace& face = half_[g];
          int side = 0;
          while (face.key[side] != key) ++side;
          place(face, side);
          queue.push(g);
        }
      }
    }
    const int n = tables_.num_vertices();
    if (std::count(placed.begin(), placed.begin() + n, 0) > 0) {
      throw SolverError("the half of the intrinsic triangulation does not reach every vertex");
    }
  }

  const Mesh& mesh_;
  const MeshTables& tables_;
  DoubleCover cover_;
  IntrinsicFlowOptions settings_;
  IntrinsicTriangulation tri_;
  std::vector<int> side_;    ///< By double vertex: 1 mesh interior, 0 loop, -1 mirror copy.
  std::vector<int> mirror_;  ///< By double vertex: its mirror image (itself on a loop).
  std::vector<int> loop_next_;
  bool solved_ = false;
  std::vector<HalfFace> half_;
  std::vector<Complex> positions_;
  std::map<std::pair<int, int>, double> rim_;  ///< Loop sides between two mesh vertices.
  std::vector<std::vector<std::pair<int, double>>> rim_midpoints_;  ///< Loop sides to midpoints.
};

}  // namespace

std::unique_ptr<FlatMetric> intrinsic_flat_metric(const Mesh& mesh, const MeshTables& tables,
                                                  const FlowOptions& options) {
  return std::make_unique<IntrinsicFlatMetric>(mesh, tables, options);
}

}  // namespace ricci::detail

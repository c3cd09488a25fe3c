#include "spline/tessellate/tessellate.h"

#include "spline/tessellate/dihedral.h"
#include "spline/tessellate/parallel_for.h"
#include "spline/tessellate/triangle_sides.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "ricci/mesh/errors.h"
#include "ricci/topology/slice.h"
#include "ricci/util/edge_key.h"
#include "ricci/util/hash.h"

namespace spline {
namespace {

// Position and normal at p (first derivatives only); where du x dv vanishes (a degenerate
// control net) the normal is taken a hair inside the face, the limit of the normals around the
// point.
SurfaceJet evaluate_with_normal(const ManifoldSpline& spline, const DomainPoint& p) {
  SurfaceJet jet = spline.evaluate(p, -1, {}, BasisDerivatives::first);
  if (jet.normal.squaredNorm() == 0.0) {
    DomainPoint inside = p;
    inside.barycentric = 0.999 * p.barycentric + Eigen::Vector3d::Constant(0.001 / 3.0);
    jet.normal = spline.evaluate(inside, -1, {}, BasisDerivatives::first).normal;
  }
  return jet;
}

Eigen::Vector3d corner_bary(int k) {
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  b[k] = 1.0;
  return b;
}

// Barycentric coordinates of the point at t from corner `from` to corner `to`.
Eigen::Vector3d edge_bary(int from, int to, double t) {
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  b[from] = 1.0 - t;
  b[to] = t;
  return b;
}

struct Layout {
  int d;
  // Interior samples of a face: lattice (a0, a1, a2), all > 0, in the order a1 = 1.., a2 = 1..
  [[nodiscard]] int interior_count() const { return (d - 1) * (d - 2) / 2; }
  [[nodiscard]] int interior_offset(int a1, int a2) const {
    // Row a1 (1..d-2) holds a2 = 1 .. d-1-a1: (d - 1 - a1) entries.
    int offset = 0;
    for (int r = 1; r < a1; ++r) offset += d - 1 - r;
    return offset + (a2 - 1);
  }
};

// TessellationOptions::reuse's samples on its reuse_faces, by domain point (bit for bit).
class EarlierSamples {
 public:
  EarlierSamples(const TessellationOptions& options, int faces) {
    const Tessellation* t = options.reuse;
    if (!t) return;
    if (options.reuse_faces.size() != static_cast<std::size_t>(faces) ||
        static_cast<Eigen::Index>(t->parameters.size()) != t->positions.rows() ||
        t->normals.rows() != t->positions.rows())
      throw ricci::InvalidInputError("tessellate: reuse_faces has " +
                                     std::to_string(options.reuse_faces.size()) +
                                     " entries for " + std::to_string(faces) +
                                     " faces, or the tessellation reused is inconsistent");
    rows_.reserve(t->parameters.size());
    for (std::size_t i = 0; i < t->parameters.size(); ++i) {
      const DomainPoint& p = t->parameters[i];
      if (p.face >= 0 && p.face < faces && options.reuse_faces[static_cast<std::size_t>(p.face)])
        rows_.emplace(key(p), static_cast<Eigen::Index>(i));
    }
  }
  // The earlier sample at p, -1 when there is none to take.
  [[nodiscard]] Eigen::Index row(const DomainPoint& p) const {
    if (rows_.empty()) return -1;
    const auto it = rows_.find(key(p));
    return it == rows_.end() ? -1 : it->second;
  }

 private:
  using Key = std::array<std::uint64_t, 4>;
  static Key key(const DomainPoint& p) {
    Key k{static_cast<std::uint64_t>(p.face), 0, 0, 0};
    std::memcpy(&k[1], p.barycentric.data(), 3 * sizeof(double));
    return k;
  }
  std::unordered_map<Key, Eigen::Index, ricci::WordsHash> rows_;
};

}  // namespace

namespace {

// By face of the splines' shared domain mesh: 1 where a function reaching it
// (ManifoldSplineSpace::reaching_faces) has control points `differ(i)` (by function index) in
// `a` and `b`; 0 elsewhere and outside the domain. `caller` names the public function in errors.
template <class Differ>
std::vector<char> faces_reached_by(const ManifoldSpline& a, const ManifoldSpline& b,
                                   const char* caller, const Differ& differ) {
  if (!a.space || a.space != b.space)
    throw ricci::InvalidInputError(std::string(caller) + ": the splines do not share a space");
  const ManifoldSplineSpace& space = *a.space;
  const Eigen::Index n = space.function_count();
  if (a.control_points.rows() != n || b.control_points.rows() != n)
    throw ricci::InvalidInputError(std::string(caller) + ": control points for " +
                                   std::to_string(n) + " functions expected");
  // The faces owning a function that differs, then the faces those reach.
  const int m = space.functions_per_face();
  std::vector<char> owner(static_cast<std::size_t>(space.face_count()), 0);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (differ(i))
      owner[static_cast<std::size_t>(space.domain_faces()[static_cast<std::size_t>(i / m)])] = 1;
  }
  std::vector<char> reached(owner.size(), 0);
  for (int f : space.domain_faces()) {
    const std::vector<int> reaching = space.reaching_faces(f);
    reached[static_cast<std::size_t>(f)] =
        std::any_of(reaching.begin(), reaching.end(),
                    [&](int g) { return owner[static_cast<std::size_t>(g)] != 0; });
  }
  return reached;
}

}  // namespace

std::vector<char> faces_evaluated_alike(const ManifoldSpline& a, const ManifoldSpline& b) {
  // Bit for bit (0.0 and -0.0 differ: a sum of zeros keeps the sign).
  const auto same = [](double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; };
  const std::vector<char> reached =
      faces_reached_by(a, b, "faces_evaluated_alike", [&](Eigen::Index i) {
        return !(same(a.control_points(i, 0), b.control_points(i, 0)) &&
                 same(a.control_points(i, 1), b.control_points(i, 1)) &&
                 same(a.control_points(i, 2), b.control_points(i, 2)));
      });
  std::vector<char> alike(reached.size(), 0);
  for (int f : a.space->domain_faces())
    alike[static_cast<std::size_t>(f)] = !reached[static_cast<std::size_t>(f)];
  return alike;
}

std::vector<char> faces_moved_farther(const ManifoldSpline& a, const ManifoldSpline& b,
                                      double distance) {
  return faces_reached_by(a, b, "faces_moved_farther", [&](Eigen::Index i) {
    return (a.control_points.row(i) - b.control_points.row(i)).norm() > distance;
  });
}

int Tessellation::edge_sample(int face, int corner, int i) const {
  const int next = (corner + 1) % 3, after = (corner + 2) % 3;
  if (i == 0) return vertex_position_[face_corner_vertex_[face][next]];
  if (i == density) return vertex_position_[face_corner_vertex_[face][after]];
  const int canonical = face_edge_reversed_[face][corner] ? density - i : i;
  return face_edge_first_[face][corner] + canonical - 1;
}

Tessellation tessellate(const ManifoldSpline& spline, const ricci::Mesh& mesh,
                        const TessellationOptions& options) {
  const int d = options.density;
  if (d < 1)
    throw ricci::InvalidInputError("tessellate: density must be >= 1, not " + std::to_string(d));
  if (!spline.space) throw ricci::InvalidInputError("tessellate: the spline has no space");
  const ManifoldSplineSpace& space = *spline.space;
  if (static_cast<int>(mesh.n_faces()) != space.face_count())
    throw ricci::InvalidInputError("tessellate: the mesh is not the spline's domain mesh");
  if (!options.skip_faces.empty() && options.skip_faces.size() != mesh.n_faces())
    throw ricci::InvalidInputError("tessellate: skip_faces has " +
                                   std::to_string(options.skip_faces.size()) + " entries for " +
                                   std::to_string(mesh.n_faces()) + " faces");
  std::vector<int> faces;
  for (int f : space.domain_faces())
    if (options.skip_faces.empty() || !options.skip_faces[static_cast<std::size_t>(f)])
      faces.push_back(f);

  Tessellation out;
  out.density = d;
  const int nf = static_cast<int>(mesh.n_faces());
  out.vertex_position_.assign(mesh.n_vertices(), -1);
  out.face_edge_first_.assign(static_cast<std::size_t>(nf), {-1, -1, -1});
  out.face_edge_reversed_.assign(static_cast<std::size_t>(nf), {0, 0, 0});
  out.face_corner_vertex_.assign(static_cast<std::size_t>(nf), {-1, -1, -1});
  std::vector<int> edge_first(mesh.n_edges(), -1), edge_start(mesh.n_edges(), -1);
  std::vector<DomainPoint>& params = out.parameters;

  // Samples: vertices and edges on first sight (evaluated from that face), then interiors.
  for (int f : faces) {
    const auto hs = ricci::face_halfedges(mesh, mesh.face_handle(f));
    auto& cv = out.face_corner_vertex_[static_cast<std::size_t>(f)];
    for (int k = 0; k < 3; ++k) cv[k] = mesh.to_vertex_handle(hs[k]).idx();
    for (int k = 0; k < 3; ++k) {
      if (out.vertex_position_[cv[k]] < 0) {
        out.vertex_position_[cv[k]] = static_cast<int>(params.size());
        params.push_back({f, corner_bary(k)});
      }
    }
    for (int k = 0; k < 3; ++k) {
      const int from = (k + 1) % 3, to = (k + 2) % 3;
      // h_{k+2} runs from corner k + 1 to corner k + 2: the edge opposite corner k.
      const int e = mesh.edge_handle(hs[to]).idx();
      if (edge_first[e] < 0) {
        edge_first[e] = static_cast<int>(params.size());
        edge_start[e] = cv[from];
        for (int i = 1; i < d; ++i) params.push_back({f, edge_bary(from, to, double(i) / d)});
      }
      out.face_edge_first_[static_cast<std::size_t>(f)][k] = edge_first[e];
      out.face_edge_reversed_[static_cast<std::size_t>(f)][k] = edge_start[e] != cv[from];
    }
  }
  const Layout layout{d};
  std::vector<int> interior_first(static_cast<std::size_t>(nf), -1);
  for (int f : faces) {
    interior_first[static_cast<std::size_t>(f)] = static_cast<int>(params.size());
    for (int a1 = 1; a1 <= d - 2; ++a1) {
      for (int a2 = 1; a2 <= d - 1 - a1; ++a2) {
        params.push_back({f, Eigen::Vector3d(d - a1 - a2, a1, a2) / d});
      }
    }
  }

  const auto np = static_cast<Eigen::Index>(params.size());
  out.positions.resize(np, 3);
  out.normals.resize(np, 3);
  const EarlierSamples earlier(options, nf);
  parallel_for(params.size(), options.threads, [&](std::size_t i) {
    const Eigen::Index from = earlier.row(params[i]);
    if (from >= 0) {
      out.positions.row(static_cast<Eigen::Index>(i)) = options.reuse->positions.row(from);
      out.normals.row(static_cast<Eigen::Index>(i)) = options.reuse->normals.row(from);
      return;
    }
    const SurfaceJet jet = evaluate_with_normal(spline, params[i]);
    out.positions.row(static_cast<Eigen::Index>(i)) = jet.position.transpose();
    out.normals.row(static_cast<Eigen::Index>(i)) = jet.normal.transpose();
  });

  // Render vertices keyed by (position, central-chart vertex at the canonical start): the two
  // sides of a cut have different chart copies of their vertices.
  const ricci::Chart& central = space.atlas().charts.at(0);
  const auto chart_vertices = static_cast<std::uint64_t>(central.positions.rows()) + 1;
  std::unordered_map<std::uint64_t, int> render_of;
  std::vector<Eigen::Vector2d> uvs;
  auto render_vertex = [&](int position, int chart_vertex, const Eigen::Vector2d& uv) {
    const std::uint64_t key = static_cast<std::uint64_t>(position) * chart_vertices +
                              static_cast<std::uint64_t>(chart_vertex + 1);
    auto [it, inserted] = render_of.emplace(key, static_cast<int>(uvs.size()));
    if (inserted) {
      uvs.push_back(uv);
      out.render_position.push_back(position);
    }
    return it->second;
  };

  out.triangles.reserve(faces.size() * static_cast<std::size_t>(d * d));
  for (int f : faces) {
    const int slot = central.slot(f);
    if (slot < 0)
      throw ricci::InvalidInputError("tessellate: the central chart lacks face " +
                                     std::to_string(f));
    std::array<int, 3> chart_corner{};
    std::array<Eigen::Vector2d, 3> x;
    for (int k = 0; k < 3; ++k) {
      chart_corner[k] = central.corners(slot, k);
      x[k] = central.positions.row(chart_corner[k]).transpose();
    }
    // Position and render index of lattice point (a0, a1, a2), a0 + a1 + a2 = d.
    auto sample = [&](int a0, int a1, int a2) -> std::pair<int, int> {
      const std::array<int, 3> a = {a0, a1, a2};
      int zeros = 0, zero = -1, one = -1;
      for (int k = 0; k < 3; ++k) {
        if (a[k] == 0) {
          ++zeros;
          zero = k;
        } else {
          one = k;
        }
      }
      if (zeros == 2) {
        const int p = out.vertex_position_[out.face_corner_vertex_[f][one]];
        return {p, render_vertex(p, chart_corner[one], x[one])};
      }
      if (zeros == 1) {
        const int from = (zero + 1) % 3, to = (zero + 2) % 3;
        const int i = a[to];
        const int p = out.edge_sample(f, zero, i);
        // uv from the canonical start so both faces on one side compute the same bits.
        const bool reversed = out.face_edge_reversed_[f][zero];
        const int start = reversed ? to : from, end = reversed ? from : to;
        const double t = double(reversed ? d - i : i) / d;
        return {p, render_vertex(p, chart_corner[start], (1.0 - t) * x[start] + t * x[end])};
      }
      const int p = interior_first[f] + layout.interior_offset(a1, a2);
      const Eigen::Vector3d b = Eigen::Vector3d(a0, a1, a2) / d;
      return {p, render_vertex(p, -1, b[0] * x[0] + b[1] * x[1] + b[2] * x[2])};
    };
    for (int a1 = 0; a1 < d; ++a1) {
      for (int a2 = 0; a2 < d - a1; ++a2) {
        const int a0 = d - a1 - a2;
        const auto p = sample(a0, a1, a2), q = sample(a0 - 1, a1 + 1, a2),
                   r = sample(a0 - 1, a1, a2 + 1);
        out.triangles.push_back({p.first, q.first, r.first});
        out.render_triangles.push_back({p.second, q.second, r.second});
        out.triangle_face.push_back(f);
        if (a0 >= 2) {
          const auto s = sample(a0 - 2, a1 + 1, a2 + 1);
          out.triangles.push_back({q.first, s.first, r.first});
          out.render_triangles.push_back({q.second, s.second, r.second});
          out.triangle_face.push_back(f);
        }
      }
    }
  }
  out.uvs.resize(static_cast<Eigen::Index>(uvs.size()), 2);
  for (std::size_t i = 0; i < uvs.size(); ++i)
    out.uvs.row(static_cast<Eigen::Index>(i)) = uvs[i].transpose();
  return out;
}

namespace {

// The edge key of triangle i's side k (corner k to corner k + 1).
std::uint64_t side_key(const Tessellation& t, std::size_t i, int k) {
  return ricci::undirected_edge_key(t.triangles[i][k], t.triangles[i][(k + 1) % 3]);
}

// Barycentric coordinates in domain face `face` of sample `p`, which lies on that face's
// closure: its parameter's nonzero corners carried to `face`'s corners by domain vertex.
Eigen::Vector3d barycentric_in(const Tessellation& t, int p, int face) {
  const DomainPoint& q = t.parameters[static_cast<std::size_t>(p)];
  if (q.face == face) return q.barycentric;
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  const auto& from = t.face_corner_vertex_[static_cast<std::size_t>(q.face)];
  const auto& to = t.face_corner_vertex_[static_cast<std::size_t>(face)];
  for (int k = 0; k < 3; ++k) {
    if (q.barycentric[k] == 0.0) continue;
    const auto j = std::find(to.begin(), to.end(), from[k]) - to.begin();
    if (j == 3)
      throw std::logic_error("refine_sharp_turns: a sample off its triangle's domain face");
    b[j] = q.barycentric[k];
  }
  return b;
}

Eigen::Vector3d triangle_normal(const Tessellation& t, const std::array<int, 3>& c) {
  const Eigen::Vector3d a = t.positions.row(c[0]), b = t.positions.row(c[1]),
                        d = t.positions.row(c[2]);
  const Eigen::Vector3d n = (b - a).cross(d - a);
  const double len = n.norm();
  return len > 0.0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

// One refinement level: the triangles marked red split 1-to-4, red closure where a triangle
// would get two split edges (unless it borders a patch), the rest bisected. Returns the reds.
int refine_level(Tessellation& t, const ManifoldSpline& spline, double cos_turn, int threads) {
  const std::size_t n = t.triangles.size();
  // By edge: its first and last triangle (-1: a single one); across[i][k]: the other one at
  // triangle i's side k.
  std::vector<std::array<int, 2>> edge_triangles;
  std::vector<std::array<int, 3>> across(n, {-1, -1, -1});
  const auto sides = sorted_triangle_sides(t.triangles, {}, static_cast<int>(t.positions.rows()));
  for (std::size_t g = 0; g < sides.size();) {
    std::size_t end = g;
    while (end < sides.size() && sides[end].first == sides[g].first) ++end;
    const std::array<int, 2> two{sides[g].second, end - g > 1 ? sides[end - 1].second : -1};
    edge_triangles.push_back(two);
    for (std::size_t s = g; s < end; ++s) {
      const auto i = static_cast<std::size_t>(sides[s].second);
      for (int k = 0; k < 3; ++k) {
        if (side_key(t, i, k) == sides[g].first)
          across[i][k] = two[0] == static_cast<int>(i) ? two[1] : two[0];
      }
    }
    g = end;
  }
  auto neighbour = [&](std::size_t i, int k) { return across[i][k]; };
  // A triangle may split 1-to-4 when it is the spline's and no patch triangle borders it.
  std::vector<char> may_split(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (t.triangle_face[i] < 0) continue;
    bool next_to_patch = false;
    for (int k = 0; k < 3; ++k) {
      const int j = neighbour(i, k);
      next_to_patch |= j >= 0 && t.triangle_face[static_cast<std::size_t>(j)] < 0;
    }
    may_split[i] = !next_to_patch;
  }
  std::vector<Eigen::Vector3d> normal(n);
  for (std::size_t i = 0; i < n; ++i) normal[i] = triangle_normal(t, t.triangles[i]);
  std::vector<char> red(n, 0);
  for (const auto& two : edge_triangles) {
    if (two[1] < 0) continue;
    const auto a = static_cast<std::size_t>(two[0]), b = static_cast<std::size_t>(two[1]);
    if (normal[a].isZero() || normal[b].isZero() || normal[a].dot(normal[b]) >= cos_turn)
      continue;
    red[a] |= may_split[a];
    red[b] |= may_split[b];
  }
  // Closure: an edge splits when a red triangle has it; two split edges make a triangle red.
  std::unordered_map<std::uint64_t, int> midpoint;  // by split edge: its new sample
  auto split_edges = [&](std::size_t i) {
    int count = 0;
    for (int k = 0; k < 3; ++k)
      count += midpoint.count(side_key(t, i, k)) > 0;
    return count;
  };
  std::vector<std::size_t> queue;
  for (std::size_t i = 0; i < n; ++i)
    if (red[i]) queue.push_back(i);
  if (queue.empty()) return 0;
  while (!queue.empty()) {
    const std::size_t i = queue.back();
    queue.pop_back();
    for (int k = 0; k < 3; ++k) {
      if (!midpoint.emplace(side_key(t, i, k), -1).second)
        continue;
      const int j = neighbour(i, k);
      if (j < 0) continue;
      const auto u = static_cast<std::size_t>(j);
      if (!red[u] && may_split[u] && split_edges(u) >= 2) {
        red[u] = 1;
        queue.push_back(u);
      }
    }
  }

  // The new samples: each split edge's domain midpoint in one of its triangles' faces.
  std::vector<DomainPoint> points;
  for (std::size_t i = 0; i < n; ++i) {
    const int face = t.triangle_face[i];
    if (face < 0) continue;
    for (int k = 0; k < 3; ++k) {
      const int a = t.triangles[i][k], b = t.triangles[i][(k + 1) % 3];
      auto it = midpoint.find(ricci::undirected_edge_key(a, b));
      if (it == midpoint.end() || it->second >= 0) continue;
      it->second = static_cast<int>(t.positions.rows() + static_cast<Eigen::Index>(points.size()));
      points.push_back({face, 0.5 * (barycentric_in(t, a, face) + barycentric_in(t, b, face))});
    }
  }
  const Eigen::Index base = t.positions.rows();
  const auto added = static_cast<Eigen::Index>(points.size());
  t.positions.conservativeResize(base + added, 3);
  t.normals.conservativeResize(base + added, 3);
  parallel_for(points.size(), threads, [&](std::size_t i) {
    const SurfaceJet jet = evaluate_with_normal(spline, points[i]);
    t.positions.row(base + static_cast<Eigen::Index>(i)) = jet.position.transpose();
    t.normals.row(base + static_cast<Eigen::Index>(i)) = jet.normal.transpose();
  });
  t.parameters.insert(t.parameters.end(), points.begin(), points.end());

  // Render midpoints by render edge: the two sides of a cut keep their own uvs.
  std::unordered_map<std::uint64_t, int> render_midpoint;
  std::vector<Eigen::Vector2d> new_uvs;
  const auto render_base = static_cast<int>(t.uvs.rows());
  auto render_mid = [&](int ra, int rb, int position) {
    auto [it, inserted] = render_midpoint.emplace(ricci::undirected_edge_key(ra, rb), 0);
    if (inserted) {
      it->second = render_base + static_cast<int>(new_uvs.size());
      new_uvs.push_back(0.5 * (t.uvs.row(ra) + t.uvs.row(rb)).transpose());
      t.render_position.push_back(position);
    }
    return it->second;
  };

  std::vector<std::array<int, 3>> triangles, render_triangles;
  std::vector<int> triangle_face;
  triangles.reserve(n + 3 * midpoint.size());
  render_triangles.reserve(triangles.capacity());
  triangle_face.reserve(triangles.capacity());
  int reds = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& p = t.triangles[i];
    const auto& r = t.render_triangles[i];
    const int face = t.triangle_face[i];
    // Midpoint (position, render) of edge k, from corner k to corner k + 1; -1: not split.
    std::array<int, 3> mp{-1, -1, -1}, mr{-1, -1, -1};
    int split = 0;
    for (int k = 0; k < 3; ++k) {
      const int k1 = (k + 1) % 3;
      auto it = midpoint.find(ricci::undirected_edge_key(p[k], p[k1]));
      if (it == midpoint.end()) continue;
      mp[k] = it->second;
      mr[k] = render_mid(r[k], r[k1], mp[k]);
      ++split;
    }
    auto emit = [&](std::array<int, 3> tri_p, std::array<int, 3> tri_r) {
      triangles.push_back(tri_p);
      render_triangles.push_back(tri_r);
      triangle_face.push_back(face);
    };
    if (split == 0) {
      emit(p, r);
    } else if (split == 3) {
      ++reds;
      for (int k = 0; k < 3; ++k) {
        const int prev = (k + 2) % 3;
        emit({p[k], mp[k], mp[prev]}, {r[k], mr[k], mr[prev]});
      }
      emit({mp[0], mp[1], mp[2]}, {mr[0], mr[1], mr[2]});
    } else if (split == 1) {
      const int k = mp[0] >= 0 ? 0 : mp[1] >= 0 ? 1 : 2;
      const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
      emit({p[k], mp[k], p[k2]}, {r[k], mr[k], r[k2]});
      emit({mp[k], p[k1], p[k2]}, {mr[k], r[k1], r[k2]});
    } else {
      // Edges k and k + 1 split (k + 2 not): the corner triangle at k + 1, and the quad
      // p[k], m_k, m_{k+1}, p[k+2] cut along its shorter diagonal.
      const int k = mp[0] < 0 ? 1 : mp[1] < 0 ? 2 : 0;
      const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
      emit({mp[k], p[k1], mp[k1]}, {mr[k], r[k1], mr[k1]});
      const double d1 = (t.positions.row(p[k]) - t.positions.row(mp[k1])).squaredNorm();
      const double d2 = (t.positions.row(mp[k]) - t.positions.row(p[k2])).squaredNorm();
      if (d1 <= d2) {
        emit({p[k], mp[k], mp[k1]}, {r[k], mr[k], mr[k1]});
        emit({p[k], mp[k1], p[k2]}, {r[k], mr[k1], r[k2]});
      } else {
        emit({p[k], mp[k], p[k2]}, {r[k], mr[k], r[k2]});
        emit({mp[k], mp[k1], p[k2]}, {mr[k], mr[k1], r[k2]});
      }
    }
  }
  t.triangles = std::move(triangles);
  t.render_triangles = std::move(render_triangles);
  t.triangle_face = std::move(triangle_face);
  t.uvs.conservativeResize(render_base + static_cast<Eigen::Index>(new_uvs.size()), 2);
  for (std::size_t i = 0; i < new_uvs.size(); ++i)
    t.uvs.row(render_base + static_cast<Eigen::Index>(i)) = new_uvs[i].transpose();
  return reds;
}

}  // namespace

int refine_sharp_turns(Tessellation& t, const ManifoldSpline& spline, double turn_deg, int levels,
                       int threads) {
  if (!(turn_deg > 0.0 && turn_deg < 180.0) || levels < 0)
    throw ricci::InvalidInputError("refine_sharp_turns: the turn must be in (0, 180) degrees and "
                                   "the levels >= 0, not " +
                                   std::to_string(turn_deg) + " and " + std::to_string(levels));
  const double cos_turn = std::cos(turn_deg * M_PI / 180.0);
  // The level kept is the deepest one that shows no more fold edges than any before it: a
  // level showing more has found a fold of the spline within a triangle, which the fit judged
  // on the coarser grid (the next level may resolve a turn the first one only split).
  int best_folds = levels > 0 ? dihedral_angles(t.triangles, t.positions).over_90_deg : 0;
  int reds = 0, best_reds = 0;
  Tessellation current = t;
  for (int level = 0; level < levels; ++level) {
    const int split = refine_level(current, spline, cos_turn, threads);
    if (split == 0) break;
    reds += split;
    const int folds = dihedral_angles(current.triangles, current.positions).over_90_deg;
    if (folds > best_folds) continue;
    best_folds = folds;
    best_reds = reds;
    t = current;
  }
  reds = best_reds;
  t.turn_splits += reds;
  return reds;
}

double max_edge_normal_jump_deg(const ManifoldSpline& spline, const ricci::Mesh& mesh,
                                int samples_per_edge, int threads,
                                const std::vector<char>& skip_faces,
                                const std::vector<double>& earlier,
                                const std::vector<char>& alike) {
  const std::vector<double> jumps =
      edge_normal_jumps_deg(spline, mesh, samples_per_edge, threads, skip_faces, earlier, alike);
  return std::max(0.0, jumps.empty() ? 0.0 : *std::max_element(jumps.begin(), jumps.end()));
}

std::vector<double> edge_normal_jumps_deg(const ManifoldSpline& spline, const ricci::Mesh& mesh,
                                          int samples_per_edge, int threads,
                                          const std::vector<char>& skip_faces,
                                          const std::vector<double>& earlier,
                                          const std::vector<char>& alike) {
  if (!earlier.empty() && (earlier.size() != mesh.n_edges() || alike.size() != mesh.n_faces()))
    throw ricci::InvalidInputError("edge_normal_jumps_deg: earlier angles for " +
                                   std::to_string(earlier.size()) + " edges and " +
                                   std::to_string(alike.size()) + " face flags, for " +
                                   std::to_string(mesh.n_edges()) + " edges and " +
                                   std::to_string(mesh.n_faces()) + " faces");
  const ManifoldSplineSpace& space = *spline.space;
  auto kept = [&](ricci::FaceHandle f) {
    return f.is_valid() && space.in_domain(f.idx()) &&
           (skip_faces.empty() || !skip_faces[static_cast<std::size_t>(f.idx())]);
  };
  struct Probe {
    DomainPoint a, b;
  };
  std::vector<Probe> probes;
  std::vector<int> probe_edge;
  std::vector<double> jumps(mesh.n_edges(), -1.0);
  const int s = std::max(1, samples_per_edge);
  for (auto e : mesh.edges()) {
    const auto h0 = mesh.halfedge_handle(e, 0), h1 = mesh.halfedge_handle(e, 1);
    const auto f0 = mesh.face_handle(h0), f1 = mesh.face_handle(h1);
    if (!kept(f0) || !kept(f1)) continue;
    jumps[static_cast<std::size_t>(e.idx())] = 0.0;
    if (!earlier.empty() && earlier[static_cast<std::size_t>(e.idx())] >= 0.0 &&
        alike[static_cast<std::size_t>(f0.idx())] && alike[static_cast<std::size_t>(f1.idx())]) {
      jumps[static_cast<std::size_t>(e.idx())] = earlier[static_cast<std::size_t>(e.idx())];
      continue;
    }
    // Corner indices of the edge's ends in each face.
    auto corner_of = [&](ricci::FaceHandle f, ricci::VertexHandle v) {
      const auto hs = ricci::face_halfedges(mesh, f);
      for (int k = 0; k < 3; ++k)
        if (mesh.to_vertex_handle(hs[k]) == v) return k;
      return -1;
    };
    const auto va = mesh.from_vertex_handle(h0), vb = mesh.to_vertex_handle(h0);
    const int a0 = corner_of(f0, va), b0 = corner_of(f0, vb);
    const int a1 = corner_of(f1, va), b1 = corner_of(f1, vb);
    for (int i = 0; i < s; ++i) {
      const double t = (i + 0.5) / s;
      probes.push_back({{f0.idx(), edge_bary(a0, b0, t)}, {f1.idx(), edge_bary(a1, b1, t)}});
      probe_edge.push_back(e.idx());
    }
  }
  std::vector<double> angle(probes.size(), 0.0);
  parallel_for(probes.size(), threads, [&](std::size_t i) {
    const Eigen::Vector3d na = spline.evaluate(probes[i].a, -1, {}, BasisDerivatives::first).normal;
    const Eigen::Vector3d nb = spline.evaluate(probes[i].b, -1, {}, BasisDerivatives::first).normal;
    if (na.squaredNorm() == 0 || nb.squaredNorm() == 0) return;
    angle[i] = ricci::angle_between(na, nb) * 180.0 / M_PI;
  });
  for (std::size_t i = 0; i < probes.size(); ++i) {
    double& jump = jumps[static_cast<std::size_t>(probe_edge[i])];
    jump = std::max(jump, angle[i]);
  }
  return jumps;
}

}  // namespace spline

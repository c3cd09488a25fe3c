#include "ricci/layout/layout_e2.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <string>
#include <vector>

#include "ricci/mesh/errors.h"

namespace ricci {
namespace {

double length_of(const Mesh& mesh, const Eigen::VectorXd& lengths, HalfedgeHandle h) {
  return lengths[mesh.edge_handle(h).idx()];
}

void check_lengths(const Mesh& mesh, const Eigen::VectorXd& lengths) {
  if (lengths.size() != static_cast<Eigen::Index>(mesh.n_edges())) {
    throw InvalidInputError("layout: " + std::to_string(lengths.size()) + " lengths for " +
                            std::to_string(mesh.n_edges()) + " edges");
  }
  for (auto f : mesh.faces()) {
    double l[3];
    int k = 0;
    for (auto h : mesh.fh_range(f)) l[k++] = length_of(mesh, lengths, h);
    for (int i = 0; i < 3; ++i) {
      if (!std::isfinite(l[i]) || l[i] <= 0.0 || l[i] > l[(i + 1) % 3] + l[(i + 2) % 3]) {
        throw InvalidInputError("layout: face " + std::to_string(f.idx()) +
                                " violates the triangle inequality or has a bad length");
      }
    }
  }
}

/// The face farthest, in hops across edges, from the boundary: seeding there halves the depth
/// of the growth compared with a boundary seed, and closure error grows with depth.
int central_face(const Mesh& mesh) {
  std::vector<int> depth(mesh.n_faces(), -1);
  std::deque<FaceHandle> queue;
  for (auto f : mesh.faces()) {
    for (auto h : mesh.fh_range(f)) {
      if (mesh.is_boundary(mesh.opposite_halfedge_handle(h)) && depth[f.idx()] < 0) {
        depth[f.idx()] = 0;
        queue.push_back(f);
      }
    }
  }
  if (queue.empty()) return 0;
  FaceHandle last = queue.front();
  while (!queue.empty()) {
    last = queue.front();
    queue.pop_front();
    for (auto g : mesh.ff_range(last)) {
      if (depth[g.idx()] < 0) {
        depth[g.idx()] = depth[last.idx()] + 1;
        queue.push_back(g);
      }
    }
  }
  return last.idx();
}

double cross(const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }

}  // namespace

double corner_angle_from_lengths(double opposite, double b, double c) {
  // Half-angle form tan(theta/2) = sqrt((s-b)(s-c) / (s(s-a))): accurate for needles, where
  // acos of the cosine law or the circle intersection's sqrt(l^2 - x^2) lose half the digits.
  const double s_a = 0.5 * (b + c - opposite), s_b = 0.5 * (opposite + c - b),
               s_c = 0.5 * (opposite + b - c), s = 0.5 * (opposite + b + c);
  return 2.0 * std::atan2(std::sqrt(std::max(0.0, s_b * s_c)), std::sqrt(std::max(0.0, s * s_a)));
}

double triangle_area_from_lengths(double a, double b, double c) {
  // Kahan's ordering of Heron's formula: accurate to a few ulps even for needles, where
  // sqrt(l^2 - x^2) in a naive circle intersection loses half the digits.
  if (a < b) std::swap(a, b);
  if (b < c) std::swap(b, c);
  if (a < b) std::swap(a, b);
  const double p = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
  return 0.25 * std::sqrt(std::max(0.0, p));
}

Eigen::Vector2d place_third_vertex(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double l_ac,
                                   double l_bc) {
  const Eigen::Vector2d ab = b - a;
  const double d = ab.norm();
  const Eigen::Vector2d e = ab / d;
  const Eigen::Vector2d n(-e.y(), e.x());
  // Foot of the altitude from the two circle equations; height from the stable area.
  const double x = (d * d + l_ac * l_ac - l_bc * l_bc) / (2.0 * d);
  const double y = 2.0 * triangle_area_from_lengths(d, l_ac, l_bc) / d;
  return a + x * e + y * n;
}

void measure_layout(const Mesh& mesh, const Eigen::VectorXd& lengths,
                    const Eigen::MatrixX2d& positions, LayoutE2Result& result) {
  result.min_signed_area = std::numeric_limits<double>::infinity();
  result.flipped_faces = 0;
  std::vector<double> angle(mesh.n_vertices(), 0.0);
  for (auto f : mesh.faces()) {
    const auto h0 = mesh.halfedge_handle(f);
    const auto h1 = mesh.next_halfedge_handle(h0);
    const int i = mesh.from_vertex_handle(h0).idx(), j = mesh.to_vertex_handle(h0).idx(),
              k = mesh.to_vertex_handle(h1).idx();
    const Eigen::Vector2d a = positions.row(i), b = positions.row(j), c = positions.row(k);
    const double area = 0.5 * cross(b - a, c - a);
    result.min_signed_area = std::min(result.min_signed_area, area);
    if (!(area > 0.0)) ++result.flipped_faces;
    const int corner[3] = {i, j, k};
    const Eigen::Vector2d p[3] = {a, b, c};
    for (int m = 0; m < 3; ++m) {
      const Eigen::Vector2d u = p[(m + 1) % 3] - p[m], v = p[(m + 2) % 3] - p[m];
      angle[corner[m]] += std::atan2(cross(u, v), u.dot(v));
    }
  }
  result.max_relative_length_error = 0.0;
  for (auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    const double d = (positions.row(mesh.to_vertex_handle(h).idx()) -
                      positions.row(mesh.from_vertex_handle(h).idx()))
                         .norm();
    const double l = lengths[e.idx()];
    result.max_relative_length_error = std::max(result.max_relative_length_error, std::abs(d - l) / l);
  }
  result.max_vertex_angle = angle.empty() ? 0.0 : *std::max_element(angle.begin(), angle.end());
}

LayoutE2Result layout_e2(const Mesh& mesh, const Eigen::VectorXd& lengths,
                         const LayoutE2Options& options) {
  if (mesh.n_faces() == 0) throw InvalidInputError("layout: mesh has no faces");
  check_lengths(mesh, lengths);
  LayoutE2Result result;
  result.seed_face = options.seed_face >= 0 ? options.seed_face : central_face(mesh);
  if (result.seed_face >= static_cast<int>(mesh.n_faces())) {
    throw InvalidInputError("layout: seed face " + std::to_string(result.seed_face) +
                            " is out of range");
  }
  result.positions = Eigen::MatrixX2d::Zero(mesh.n_vertices(), 2);
  std::vector<char> placed(mesh.n_vertices(), 0), reached(mesh.n_faces(), 0);

  const FaceHandle seed(result.seed_face);
  const auto h0 = mesh.halfedge_handle(seed);
  const auto a = mesh.from_vertex_handle(h0), b = mesh.to_vertex_handle(h0);
  const auto c = mesh.to_vertex_handle(mesh.next_halfedge_handle(h0));
  result.positions.row(a.idx()) = Eigen::RowVector2d(0.0, 0.0);
  result.positions.row(b.idx()) = Eigen::RowVector2d(length_of(mesh, lengths, h0), 0.0);
  result.positions.row(c.idx()) = place_third_vertex(
      Eigen::Vector2d::Zero(), Eigen::Vector2d(length_of(mesh, lengths, h0), 0.0),
      length_of(mesh, lengths, mesh.prev_halfedge_handle(h0)),
      length_of(mesh, lengths, mesh.next_halfedge_handle(h0)));
  placed[a.idx()] = placed[b.idx()] = placed[c.idx()] = 1;
  reached[seed.idx()] = 1;
  std::deque<FaceHandle> queue{seed};
  size_t reached_count = 1;
  while (!queue.empty()) {
    const FaceHandle f = queue.front();
    queue.pop_front();
    for (auto h : mesh.fh_range(f)) {
      const auto o = mesh.opposite_halfedge_handle(h);
      const auto g = mesh.face_handle(o);
      if (!g.is_valid() || reached[g.idx()]) continue;
      reached[g.idx()] = 1;
      ++reached_count;
      queue.push_back(g);
      const auto w = mesh.to_vertex_handle(mesh.next_halfedge_handle(o));
      if (placed[w.idx()]) continue;
      const Eigen::Vector2d pa = result.positions.row(mesh.from_vertex_handle(o).idx());
      const Eigen::Vector2d pb = result.positions.row(mesh.to_vertex_handle(o).idx());
      result.positions.row(w.idx()) =
          place_third_vertex(pa, pb, length_of(mesh, lengths, mesh.prev_halfedge_handle(o)),
                             length_of(mesh, lengths, mesh.next_halfedge_handle(o)));
      placed[w.idx()] = 1;
    }
  }
  if (reached_count != mesh.n_faces()) {
    throw TopologyError("layout: " + std::to_string(mesh.n_faces() - reached_count) +
                        " faces cannot be reached from seed face " +
                        std::to_string(result.seed_face) + " (mesh not connected)");
  }
  measure_layout(mesh, lengths, result.positions, result);
  return result;
}

}  // namespace ricci

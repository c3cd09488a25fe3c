#include "ricci/hyperbolic/layout_h2.h"

#include <cmath>
#include <deque>
#include <string>
#include <vector>

#include "ricci/mesh/errors.h"
#include "ricci/metric/geometry.h"

namespace ricci {
namespace {

/// Corner angle at from_vertex(h) of h's face, from the face's hyperbolic lengths.
double angle_at_from(const Mesh& mesh, const Eigen::VectorXd& lengths, HalfedgeHandle h) {
  const HalfedgeHandle h1 = mesh.next_halfedge_handle(h), h2 = mesh.next_halfedge_handle(h1);
  // Triangle with vertices 0 = from(h), 1 = to(h), 2 = to(h1); l[k] opposite vertex k.
  const double l[3] = {lengths[mesh.edge_handle(h1).idx()], lengths[mesh.edge_handle(h2).idx()],
                       lengths[mesh.edge_handle(h).idx()]};
  double theta[3];
  if (!triangle_angles(Geometry::Hyperbolic, l, theta)) {
    throw InvalidInputError("layout_h2: face " + std::to_string(mesh.face_handle(h).idx()) +
                            " violates the hyperbolic triangle inequality");
  }
  return theta[0];
}

/// Places to_vertex(next(h)) given from(h) and to(h) at p and q.
Complex place_across(const Mesh& mesh, const Eigen::VectorXd& lengths, HalfedgeHandle h,
                     Complex p, Complex q) {
  const Mobius to_centre = disk_to_centre(p, q);
  const double l_pw = lengths[mesh.edge_handle(mesh.prev_halfedge_handle(h)).idx()];
  const Complex at_centre = std::polar(disk_radius(l_pw), angle_at_from(mesh, lengths, h));
  return to_centre.inverse()(at_centre);
}

}  // namespace

int central_face_of(const Mesh& mesh) {
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

Complex hyperbolic_centre(const Eigen::VectorXcd& points, int iterations) {
  Complex c = 0.0;
  for (int k = 1; k <= iterations; ++k) {
    const Mobius to_c = Mobius::from_rotation_point(0.0, c);
    Complex far = 0.0;
    for (Eigen::Index i = 0; i < points.size(); ++i) {
      const Complex z = to_c(points[i]);
      if (std::abs(z) > std::abs(far)) far = z;
    }
    if (std::abs(far) == 0.0) break;
    const double d = 2.0 * std::atanh(std::abs(far));
    c = to_c.inverse()(std::polar(disk_radius(d / (k + 1)), std::arg(far)));
  }
  return c;
}

LayoutH2Result layout_h2(const Mesh& mesh, const Eigen::VectorXd& edge_lengths,
                         const LayoutH2Options& options) {
  if (options.seed_face < 0 && options.recentre) {
    LayoutH2Options first = options;
    first.recentre = false;
    const LayoutH2Result draft = layout_h2(mesh, edge_lengths, first);
    const Complex c = hyperbolic_centre(draft.positions);
    int nearest = 0;
    for (Eigen::Index i = 0; i < draft.positions.size(); ++i) {
      if (disk_distance(draft.positions[i], c) < disk_distance(draft.positions[nearest], c)) {
        nearest = static_cast<int>(i);
      }
    }
    for (auto h : mesh.voh_range(VertexHandle(nearest))) {
      if (!mesh.is_boundary(h)) {
        first.seed_face = mesh.face_handle(h).idx();
        break;
      }
    }
    return layout_h2(mesh, edge_lengths, first);
  }
  if (edge_lengths.size() != static_cast<Eigen::Index>(mesh.n_edges())) {
    throw InvalidInputError("layout_h2: " + std::to_string(edge_lengths.size()) +
                            " lengths for " + std::to_string(mesh.n_edges()) + " edges");
  }
  LayoutH2Result result;
  result.seed_face = options.seed_face >= 0 ? options.seed_face : central_face_of(mesh);
  if (result.seed_face >= static_cast<int>(mesh.n_faces())) {
    throw InvalidInputError("layout_h2: seed face " + std::to_string(result.seed_face) +
                            " out of range");
  }
  result.positions = Eigen::VectorXcd::Constant(mesh.n_vertices(), Complex(NAN, NAN));
  std::vector<char> placed(mesh.n_vertices(), 0), reached(mesh.n_faces(), 0);
  const FaceHandle seed(result.seed_face);
  const HalfedgeHandle h0 = mesh.halfedge_handle(seed);
  const int a = mesh.from_vertex_handle(h0).idx(), b = mesh.to_vertex_handle(h0).idx();
  result.positions[a] = 0.0;
  result.positions[b] = disk_radius(edge_lengths[mesh.edge_handle(h0).idx()]);
  placed[a] = placed[b] = 1;
  reached[seed.idx()] = 1;
  std::deque<HalfedgeHandle> queue{h0};  // a halfedge whose two ends are placed, in a new face
  int reached_count = 1;
  while (!queue.empty()) {
    const HalfedgeHandle h = queue.front();
    queue.pop_front();
    const int w = mesh.to_vertex_handle(mesh.next_halfedge_handle(h)).idx();
    if (!placed[w]) {
      result.positions[w] =
          place_across(mesh, edge_lengths, h, result.positions[mesh.from_vertex_handle(h).idx()],
                       result.positions[mesh.to_vertex_handle(h).idx()]);
      placed[w] = 1;
    }
    for (auto g : mesh.fh_range(mesh.face_handle(h))) {
      const HalfedgeHandle o = mesh.opposite_halfedge_handle(g);
      if (mesh.is_boundary(o) || reached[mesh.face_handle(o).idx()]) continue;
      reached[mesh.face_handle(o).idx()] = 1;
      ++reached_count;
      queue.push_back(o);
    }
  }
  if (reached_count != static_cast<int>(mesh.n_faces())) {
    throw TopologyError("layout_h2: " + std::to_string(mesh.n_faces() - reached_count) +
                        " faces cannot be reached from seed face " +
                        std::to_string(result.seed_face) + " (mesh not connected)");
  }
  measure_layout_h2(mesh, edge_lengths, result.positions, result);
  return result;
}

void measure_layout_h2(const Mesh& mesh, const Eigen::VectorXd& edge_lengths,
                       const Eigen::VectorXcd& positions, LayoutH2Result& result) {
  result.min_signed_area = INFINITY;
  result.flipped_faces = 0;
  for (auto f : mesh.faces()) {
    Complex z[3];
    int k = 0;
    for (auto v : mesh.fv_range(f)) z[k++] = positions[v.idx()];
    const double area = 0.5 * std::imag(std::conj(z[1] - z[0]) * (z[2] - z[0]));
    result.min_signed_area = std::min(result.min_signed_area, area);
    if (!(area > 0)) ++result.flipped_faces;
  }
  result.max_relative_length_error = 0.0;
  for (auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    const double d = disk_distance(positions[mesh.from_vertex_handle(h).idx()],
                                   positions[mesh.to_vertex_handle(h).idx()]);
    result.max_relative_length_error =
        std::max(result.max_relative_length_error,
                 std::abs(d - edge_lengths[e.idx()]) / edge_lengths[e.idx()]);
  }
  result.max_radius = positions.cwiseAbs().maxCoeff();
}

}  // namespace ricci

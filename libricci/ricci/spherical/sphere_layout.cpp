#include "ricci/spherical/sphere_layout.h"

#include <cmath>
#include <deque>
#include <string>
#include <vector>

#include "ricci/mesh/errors.h"
#include "ricci/metric/geometry.h"

namespace ricci {
namespace {

double angle_at_from(const Mesh& mesh, const Eigen::VectorXd& lengths, HalfedgeHandle h) {
  const HalfedgeHandle h1 = mesh.next_halfedge_handle(h), h2 = mesh.next_halfedge_handle(h1);
  const double l[3] = {lengths[mesh.edge_handle(h1).idx()], lengths[mesh.edge_handle(h2).idx()],
                       lengths[mesh.edge_handle(h).idx()]};
  double theta[3];
  if (!triangle_angles(Geometry::spherical, l, theta)) {
    throw InvalidInputError("layout_sphere: face " + std::to_string(mesh.face_handle(h).idx()) +
                            " violates the spherical triangle inequality");
  }
  return theta[0];
}

/// The point at distance `d` from p, at angle `angle` counter-clockwise (seen from outside) from
/// the direction of q.
Eigen::Vector3d rotate_from(const Eigen::Vector3d& p, const Eigen::Vector3d& q, double d,
                            double angle) {
  const Eigen::Vector3d t = (q - q.dot(p) * p).normalized();
  const Eigen::Vector3d n = p.cross(t);
  return (std::cos(d) * p + std::sin(d) * (std::cos(angle) * t + std::sin(angle) * n)).normalized();
}

/// Moves the centroid towards 0 by dilations of stereographic coordinates along its direction
/// (a fixed-point iteration; every step is a Möbius map of S2, so conformality is kept).
void centre_on_sphere(Eigen::MatrixX3d& p, int iterations) {
  for (int it = 0; it < iterations; ++it) {
    const Eigen::Vector3d c = p.colwise().mean();
    if (c.norm() < 1e-12) return;
    const Eigen::Vector3d axis = c.normalized();
    // Stereographic projection from -axis, scale by k > 1 (pushes points away from +axis, the
    // equator to height -|c|), back.
    const double k = std::sqrt((1.0 + std::min(c.norm(), 0.9)) / (1.0 - std::min(c.norm(), 0.9)));
    for (Eigen::Index i = 0; i < p.rows(); ++i) {
      const Eigen::Vector3d x = p.row(i);
      const double h = x.dot(axis);
      const Eigen::Vector3d tangent = x - h * axis;
      const double r = tangent.norm() / (1.0 + h);  // stereographic radius from -axis
      if (!(r > 0) && h < 0) continue;              // the pole -axis stays
      const double r2 = k * r;
      const double h2 = (1.0 - r2 * r2) / (1.0 + r2 * r2);
      const double s2 = 2.0 * r2 / (1.0 + r2 * r2);
      const Eigen::Vector3d dir = tangent.norm() > 0 ? Eigen::Vector3d(tangent.normalized()) : Eigen::Vector3d::Zero();
      p.row(i) = (h2 * axis + s2 * dir).transpose();
    }
  }
}

}  // namespace

double sphere_distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return angle_between(a, b);
}

SphereLayoutResult layout_sphere(const Mesh& mesh, const Eigen::VectorXd& edge_lengths,
                                 const SphereLayoutOptions& options) {
  if (edge_lengths.size() != static_cast<Eigen::Index>(mesh.n_edges())) {
    throw InvalidInputError("layout_sphere: lengths do not match the edges");
  }
  if (options.seed_face < 0 || options.seed_face >= static_cast<int>(mesh.n_faces())) {
    throw InvalidInputError("layout_sphere: seed face " + std::to_string(options.seed_face) +
                            " out of range");
  }
  SphereLayoutResult result;
  result.positions = Eigen::MatrixX3d::Constant(mesh.n_vertices(), 3, NAN);
  std::vector<char> placed(mesh.n_vertices(), 0), reached(mesh.n_faces(), 0);
  const HalfedgeHandle h0 = mesh.halfedge_handle(FaceHandle(options.seed_face));
  const int a = mesh.from_vertex_handle(h0).idx(), b = mesh.to_vertex_handle(h0).idx();
  const double l0 = edge_lengths[mesh.edge_handle(h0).idx()];
  result.positions.row(a) = Eigen::RowVector3d(0, 0, 1);
  result.positions.row(b) = Eigen::RowVector3d(std::sin(l0), 0, std::cos(l0));
  placed[a] = placed[b] = 1;
  reached[options.seed_face] = 1;
  std::deque<HalfedgeHandle> queue{h0};
  while (!queue.empty()) {
    const HalfedgeHandle h = queue.front();
    queue.pop_front();
    const int w = mesh.to_vertex_handle(mesh.next_halfedge_handle(h)).idx();
    if (!placed[w]) {
      const Eigen::Vector3d p = result.positions.row(mesh.from_vertex_handle(h).idx());
      const Eigen::Vector3d q = result.positions.row(mesh.to_vertex_handle(h).idx());
      const double d = edge_lengths[mesh.edge_handle(mesh.prev_halfedge_handle(h)).idx()];
      result.positions.row(w) = rotate_from(p, q, d, angle_at_from(mesh, edge_lengths, h)).transpose();
      placed[w] = 1;
    }
    for (auto g : mesh.fh_range(mesh.face_handle(h))) {
      const HalfedgeHandle o = mesh.opposite_halfedge_handle(g);
      if (mesh.is_boundary(o)) throw TopologyError("layout_sphere: the mesh has a boundary");
      if (reached[mesh.face_handle(o).idx()]) continue;
      reached[mesh.face_handle(o).idx()] = 1;
      queue.push_back(o);
    }
  }
  for (auto v : mesh.vertices()) {
    if (!placed[v.idx()]) throw TopologyError("layout_sphere: the mesh is not connected");
  }
  if (options.centre) centre_on_sphere(result.positions, options.max_centring_iterations);
  result.min_orientation = INFINITY;
  for (auto f : mesh.faces()) {
    Eigen::Matrix3d m;
    int k = 0;
    for (auto v : mesh.fv_range(f)) m.col(k++) = result.positions.row(v.idx()).transpose();
    const double det = m.determinant();
    result.min_orientation = std::min(result.min_orientation, det);
    if (!(det > 0)) ++result.flipped_faces;
  }
  for (auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    const double d = sphere_distance(result.positions.row(mesh.from_vertex_handle(h).idx()),
                                     result.positions.row(mesh.to_vertex_handle(h).idx()));
    result.max_relative_length_error = std::max(
        result.max_relative_length_error, std::abs(d - edge_lengths[e.idx()]) / edge_lengths[e.idx()]);
  }
  result.max_radius_error = (result.positions.rowwise().norm().array() - 1.0).abs().maxCoeff();
  result.centroid_norm = Eigen::Vector3d(result.positions.colwise().mean()).norm();
  return result;
}

}  // namespace ricci

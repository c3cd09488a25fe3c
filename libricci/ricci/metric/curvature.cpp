#include "ricci/metric/curvature.h"

#include <string>

#include "ricci/mesh/errors.h"

namespace ricci {

std::string to_string(Geometry geometry) {
  switch (geometry) {
    case Geometry::euclidean:
      return "euclidean";
    case Geometry::hyperbolic:
      return "hyperbolic";
    default: return "spherical";
  }
}

namespace {

void face_lengths(const MeshTables& t, const EdgeLengths& lengths, int f, double l[3]) {
  for (int k = 0; k < 3; ++k) l[k] = lengths[t.face_edges(f, k)];
}

[[noreturn]] void throw_bad_face(const MeshTables& t, int f, const double l[3], Geometry g) {
  throw InvalidInputError("face " + std::to_string(f) + " (vertices " +
                          std::to_string(t.face_vertices(f, 0)) + " " +
                          std::to_string(t.face_vertices(f, 1)) + " " +
                          std::to_string(t.face_vertices(f, 2)) + ") has lengths " +
                          std::to_string(l[0]) + " " + std::to_string(l[1]) + " " +
                          std::to_string(l[2]) + " that are not a " + to_string(g) + " triangle");
}

}  // namespace

Eigen::MatrixX3d corner_angles(const MeshTables& t, const EdgeLengths& lengths, Geometry g) {
  if (lengths.size() != t.num_edges()) {
    throw InvalidInputError("edge lengths have " + std::to_string(lengths.size()) +
                            " entries for " + std::to_string(t.num_edges()) + " edges");
  }
  Eigen::MatrixX3d angles(t.num_faces(), 3);
  for (int f = 0; f < t.num_faces(); ++f) {
    double l[3], theta[3];
    face_lengths(t, lengths, f, l);
    if (!triangle_angles(g, l, theta)) throw_bad_face(t, f, l, g);
    for (int k = 0; k < 3; ++k) angles(f, k) = theta[k];
  }
  return angles;
}

Eigen::VectorXd vertex_curvature(const MeshTables& t, const Eigen::MatrixX3d& angles) {
  Eigen::VectorXd K(t.num_vertices());
  for (int v = 0; v < t.num_vertices(); ++v) K[v] = t.is_boundary_vertex[v] ? M_PI : 2.0 * M_PI;
  for (int f = 0; f < t.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) K[t.face_vertices(f, k)] -= angles(f, k);
  }
  return K;
}

Eigen::VectorXd vertex_curvature(const MeshTables& t, const EdgeLengths& lengths, Geometry g) {
  return vertex_curvature(t, corner_angles(t, lengths, g));
}

Eigen::VectorXd face_areas(const MeshTables& t, const EdgeLengths& lengths, Geometry g) {
  const Eigen::MatrixX3d angles = corner_angles(t, lengths, g);
  Eigen::VectorXd areas(t.num_faces());
  for (int f = 0; f < t.num_faces(); ++f) {
    double l[3];
    face_lengths(t, lengths, f, l);
    const double theta[3] = {angles(f, 0), angles(f, 1), angles(f, 2)};
    areas[f] = triangle_area(g, l, theta);
  }
  return areas;
}

double gauss_bonnet_residual(const MeshTables& t, const EdgeLengths& lengths, Geometry g) {
  const double total_curvature = vertex_curvature(t, lengths, g).sum();
  const double total_area = face_areas(t, lengths, g).sum();
  return total_curvature + curvature_sign(g) * total_area - 2.0 * M_PI * t.euler_characteristic;
}

Eigen::VectorXd vertex_curvature(const Mesh& mesh, const EdgeLengths& lengths, Geometry g) {
  return vertex_curvature(build_mesh_tables(mesh), lengths, g);
}

double gauss_bonnet_residual(const Mesh& mesh, const EdgeLengths& lengths, Geometry g) {
  return gauss_bonnet_residual(build_mesh_tables(mesh), lengths, g);
}

}  // namespace ricci

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>

#include <Eigen/Geometry>

#include "ricci/mesh/cgal_convert.h"
#include "ricci/mesh/simplify.h"

namespace ricci {
namespace {

using cgal::Point3;
using cgal::SurfaceMesh;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<SurfaceMesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<cgal::Kernel, Primitive>>;

// Barycentric coordinates of p (on the triangle's plane) with respect to a, b, c.
Eigen::Vector3d barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c) {
  Eigen::Vector3d n = (b - a).cross(c - a);
  double area2 = n.squaredNorm();
  if (area2 == 0.0) return Eigen::Vector3d(1.0, 0.0, 0.0);
  double wa = n.dot((b - p).cross(c - p)) / area2;
  double wb = n.dot((c - p).cross(a - p)) / area2;
  return Eigen::Vector3d(wa, wb, 1.0 - wa - wb);
}

}  // namespace

std::vector<SurfacePoint> closest_points(const Mesh& mesh, const Eigen::MatrixX3d& queries) {
  SurfaceMesh sm = cgal::to_surface_mesh(mesh);  // same face order as `mesh`
  Tree tree(faces(sm).first, faces(sm).second, sm);
  tree.accelerate_distance_queries();
  std::vector<SurfacePoint> result(static_cast<size_t>(queries.rows()));
  for (Eigen::Index i = 0; i < queries.rows(); ++i) {
    Point3 q(queries(i, 0), queries(i, 1), queries(i, 2));
    auto [closest, face] = tree.closest_point_and_primitive(q);
    SurfacePoint& out = result[static_cast<size_t>(i)];
    out.face = static_cast<int>(face.idx());
    out.point = Eigen::Vector3d(closest.x(), closest.y(), closest.z());
    out.distance = std::sqrt(CGAL::squared_distance(q, closest));
    FaceHandle f = mesh.face_handle(out.face);
    std::array<Eigen::Vector3d, 3> corners;
    int k = 0;
    for (auto v : mesh.fv_range(f)) corners[k++] = to_eigen(mesh.point(v));
    out.barycentric = barycentric(out.point, corners[0], corners[1], corners[2]);
  }
  return result;
}

}  // namespace ricci

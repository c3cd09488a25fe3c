#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>

#include <Eigen/Geometry>
#include <iterator>
#include <string>
#include <vector>

#include "ricci/mesh/cgal_convert.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/simplify.h"
#include "ricci/util/parallel.h"

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

std::array<Eigen::Vector3d, 3> corners_of(const Mesh& mesh, int face) {
  std::array<Eigen::Vector3d, 3> corners;
  int k = 0;
  for (auto v : mesh.fv_range(mesh.face_handle(face))) corners[k++] = to_eigen(mesh.point(v));
  return corners;
}

SurfacePoint surface_point(const Mesh& mesh, int face, const Eigen::Vector3d& point,
                           const Eigen::Vector3d& query) {
  SurfacePoint out;
  out.face = face;
  out.point = point;
  out.distance = (query - point).norm();
  const auto c = corners_of(mesh, face);
  out.barycentric = barycentric(point, c[0], c[1], c[2]);
  return out;
}

Eigen::Vector3d face_normal(const Mesh& mesh, int face) {
  const auto c = corners_of(mesh, face);
  return (c[1] - c[0]).cross(c[2] - c[0]);
}

// The nearest point of the faces within `radius` of q whose normal agrees with n; face -1 when
// there is none.
SurfacePoint nearest_agreeing(const Mesh& mesh, const Tree& tree, const Eigen::Vector3d& q,
                              const Eigen::Vector3d& n, double radius) {
  const CGAL::Bbox_3 box(q.x() - radius, q.y() - radius, q.z() - radius, q.x() + radius,
                         q.y() + radius, q.z() + radius);
  std::vector<Tree::Primitive_id> near;
  tree.all_intersected_primitives(box, std::back_inserter(near));
  SurfacePoint best;
  const Point3 p(q.x(), q.y(), q.z());
  for (const auto& id : near) {
    const int face = static_cast<int>(id.idx());
    if (!(face_normal(mesh, face).dot(n) > 0.0)) continue;
    const auto c = corners_of(mesh, face);
    const cgal::Kernel::Triangle_3 t(Point3(c[0].x(), c[0].y(), c[0].z()),
                                     Point3(c[1].x(), c[1].y(), c[1].z()),
                                     Point3(c[2].x(), c[2].y(), c[2].z()));
    if (t.is_degenerate()) continue;
    const Point3 x = cgal::Kernel().construct_projected_point_3_object()(t, p);
    const Eigen::Vector3d point(x.x(), x.y(), x.z());
    const double d = (point - q).norm();
    if (best.face >= 0 && !(d < best.distance)) continue;
    best = surface_point(mesh, face, point, q);
  }
  return best;
}

}  // namespace

std::vector<SurfacePoint> closest_points(const Mesh& mesh, const Eigen::MatrixX3d& queries) {
  return closest_points(mesh, queries, Eigen::MatrixX3d::Zero(queries.rows(), 3), 0.0);
}

std::vector<SurfacePoint> closest_points(const Mesh& mesh, const Eigen::MatrixX3d& queries,
                                         const Eigen::MatrixX3d& normals, double search_radius) {
  if (normals.rows() != queries.rows()) {
    throw InvalidInputError("closest_points: " + std::to_string(normals.rows()) +
                            " normals for " + std::to_string(queries.rows()) + " points");
  }
  SurfaceMesh sm = cgal::to_surface_mesh(mesh);  // same face order as `mesh`
  Tree tree(faces(sm).first, faces(sm).second, sm);
  // Both trees built before the queries, which then only read them (each writes its own slot).
  // The hints' search tree first, from the faces in the mesh's order (the AABB build reorders
  // them): between equally near faces (a point over a shared edge) the hint decides the face.
  tree.accelerate_distance_queries();
  tree.build();
  std::vector<SurfacePoint> result(static_cast<size_t>(queries.rows()));
  parallel_for(result.size(), 0, [&](std::size_t k) {
    const auto i = static_cast<Eigen::Index>(k);
    const Eigen::Vector3d q = queries.row(i).transpose();
    auto [closest, face] = tree.closest_point_and_primitive(Point3(q.x(), q.y(), q.z()));
    SurfacePoint& out = result[static_cast<size_t>(i)];
    out = surface_point(mesh, static_cast<int>(face.idx()),
                        Eigen::Vector3d(closest.x(), closest.y(), closest.z()), q);
    const Eigen::Vector3d n = normals.row(i).transpose();
    if (search_radius > 0.0 && n.squaredNorm() > 0.0 &&
        !(face_normal(mesh, out.face).dot(n) > 0.0)) {
      const SurfacePoint agreeing = nearest_agreeing(mesh, tree, q, n, search_radius);
      if (agreeing.face >= 0) out = agreeing;
    }
  });
  return result;
}

}  // namespace ricci

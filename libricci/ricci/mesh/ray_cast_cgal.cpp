#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>

#include <cmath>
#include <limits>

#include "ricci/mesh/cgal_convert.h"
#include "ricci/mesh/ray_cast.h"

namespace ricci {
namespace {

using cgal::Point3;
using cgal::SurfaceMesh;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<SurfaceMesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<cgal::Kernel, Primitive>>;
using Ray = cgal::Kernel::Ray_3;
using Vector3 = cgal::Kernel::Vector_3;

// Distance from `origin` along `direction` to the first face other than `self`, +inf for none.
double first_hit(const Tree& tree, const Point3& origin, const Vector3& direction,
                 SurfaceMesh::Face_index self) {
  const auto skip = [self](SurfaceMesh::Face_index f) { return f == self; };
  const auto hit = tree.first_intersection(Ray(origin, direction), skip);
  if (!hit) return std::numeric_limits<double>::infinity();
  if (const Point3* p = boost::get<Point3>(&hit->first))
    return std::sqrt(CGAL::squared_distance(origin, *p));
  return 0.0;  // a segment: the ray runs within a face
}

}  // namespace

Eigen::VectorXd face_thickness(const Mesh& mesh) {
  const SurfaceMesh sm = cgal::to_surface_mesh(mesh);  // same face order as `mesh`
  Tree tree(faces(sm).first, faces(sm).second, sm);
  Eigen::VectorXd thickness(static_cast<Eigen::Index>(mesh.n_faces()));
  for (auto f : faces(sm)) {
    const auto h = sm.halfedge(f);
    const Point3& a = sm.point(sm.source(h));
    const Point3& b = sm.point(sm.target(h));
    const Point3& c = sm.point(sm.target(sm.next(h)));
    const Vector3 n = CGAL::cross_product(b - a, c - a);
    double t = std::numeric_limits<double>::infinity();
    if (n.squared_length() > 0.0) {
      const Point3 centroid = CGAL::centroid(a, b, c);
      t = std::min(first_hit(tree, centroid, n, f), first_hit(tree, centroid, -n, f));
    }
    thickness[static_cast<Eigen::Index>(f.idx())] = t;
  }
  return thickness;
}

}  // namespace ricci

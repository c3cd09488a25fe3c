// face_thickness: the distance to the opposite sheet, seen from every face.
#include <gtest/gtest.h>

#include <cmath>

#include "ricci/mesh/primitives.h"
#include "ricci/mesh/ray_cast.h"

namespace ricci {
namespace {

// A sphere squashed into a plate `thickness` thick.
Mesh plate(double thickness) {
  Mesh m = make_icosphere(4);
  for (auto v : m.vertices()) {
    auto p = m.point(v);
    m.set_point(v, Mesh::Point(p[0], p[1], 0.5 * thickness * p[2]));
  }
  return m;
}

TEST(FaceThickness, PlateCentreIsItsThicknessAndTheSphereItsDiameter) {
  const Mesh m = plate(0.1);
  const Eigen::VectorXd t = face_thickness(m);
  ASSERT_EQ(t.size(), static_cast<Eigen::Index>(m.n_faces()));
  int centre = 0;
  for (auto f : m.faces()) {
    const Eigen::Vector3d c = to_eigen(m.calc_face_centroid(f));
    if (std::hypot(c.x(), c.y()) > 0.3) continue;
    ++centre;
    // Both sheets there are nearly flat: the ray along the normal meets the other one.
    EXPECT_NEAR(t[f.idx()], 0.1, 0.01) << "face " << f.idx();
  }
  EXPECT_GT(centre, 10);
  // Scaling the mesh scales the thickness.
  Mesh big = m;
  for (auto v : big.vertices()) big.set_point(v, 1000.0 * big.point(v));
  EXPECT_NEAR(face_thickness(big).maxCoeff(), 1000.0 * t.maxCoeff(), 1e-6 * 1000.0);
  // On a round sphere the thickness is about its diameter (the chord through the centre).
  const Eigen::VectorXd d = face_thickness(make_icosphere(3));
  EXPECT_NEAR(d.minCoeff(), 2.0, 0.05);
  EXPECT_LE(d.maxCoeff(), 2.0 + 1e-9);
}

}  // namespace
}  // namespace ricci

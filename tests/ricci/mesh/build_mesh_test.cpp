// build_mesh(): triangulation by ear clipping, consistent (outward) orientation, stripping of
// unreferenced vertices, typed refusals; and the polygon triangulator on its own.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "procedural_soups.h"
#include "ricci/mesh/build_mesh.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/triangulate_polygon.h"

namespace {

using namespace ricci_test;

double signed_volume(const ricci::Mesh& mesh) {
  double volume = 0;
  for (const auto f : mesh.faces()) {
    std::vector<Eigen::Vector3d> p;
    for (const auto v : mesh.fv_range(f)) p.push_back(ricci::to_eigen(mesh.point(v)));
    volume += p[0].dot(p[1].cross(p[2])) / 6;
  }
  return volume;
}

TEST(BuildMesh, TetrahedronKeepsItsFacesAndOrientation) {
  const auto result = ricci::build_mesh_with_report(tetrahedron());
  EXPECT_EQ(result.mesh.n_vertices(), 4u);
  EXPECT_EQ(result.mesh.n_faces(), 4u);
  EXPECT_EQ(result.faces_flipped, 0);
  EXPECT_NEAR(signed_volume(result.mesh), 1.0 / 6.0, 1e-15);
}

TEST(BuildMesh, InconsistentAndInwardFacesAreFlippedOutward) {
  auto soup = tetrahedron();
  std::reverse(soup.faces[2].begin(), soup.faces[2].end());
  auto result = ricci::build_mesh_with_report(soup);
  EXPECT_EQ(result.faces_flipped, 1);
  EXPECT_NEAR(signed_volume(result.mesh), 1.0 / 6.0, 1e-15);
  for (auto& face : soup.faces) std::reverse(face.begin(), face.end());  // now 3 inward, 1 out
  result = ricci::build_mesh_with_report(soup);
  EXPECT_EQ(result.faces_flipped, 3);
  EXPECT_NEAR(signed_volume(result.mesh), 1.0 / 6.0, 1e-15);
}

TEST(BuildMesh, QuadTorusIsTriangulatedWithTheSameTopology) {
  const auto result = ricci::build_mesh_with_report(torus(10, 6, true));
  EXPECT_EQ(result.polygons_triangulated, 60);
  EXPECT_EQ(result.mesh.n_faces(), 120u);
  EXPECT_EQ(euler_characteristic(result.mesh), 0);
  EXPECT_GT(signed_volume(result.mesh), 0);
  for (const auto e : result.mesh.edges()) EXPECT_FALSE(result.mesh.is_boundary(e));
}

TEST(BuildMesh, UnreferencedVerticesAreDroppedAndMappedBack) {
  auto soup = tetrahedron();
  soup.positions.insert(soup.positions.begin(), Eigen::Vector3d(9, 9, 9));
  soup.positions.emplace_back(NAN, 0, 0);
  for (auto& face : soup.faces)
    for (int& v : face) ++v;
  const auto result = ricci::build_mesh_with_report(soup);
  EXPECT_EQ(result.unreferenced_removed, 2);
  EXPECT_EQ(result.input_vertex, (std::vector<int>{1, 2, 3, 4}));
  for (const auto v : result.mesh.vertices())
    EXPECT_EQ(ricci::to_eigen(result.mesh.point(v)), soup.positions[result.input_vertex[v.idx()]]);
}

TEST(BuildMesh, RefusesWhatIsNotACleanSurfaceWithTypedErrors) {
  auto named = [](ricci::PolygonSoup soup) {
    soup.source = "x.off";
    return soup;
  };
  EXPECT_THROW((void)ricci::build_mesh(named(mobius(8))), ricci::TopologyError);
  auto two = tetrahedron();
  append(two, tetrahedron(), {3, 0, 0});
  EXPECT_THROW((void)ricci::build_mesh(named(two)), ricci::TopologyError);
  auto nan = tetrahedron();
  nan.positions[1].x() = NAN;
  try {
    (void)ricci::build_mesh(named(nan));
    ADD_FAILURE() << "no exception";
  } catch (const ricci::TopologyError&) {
    ADD_FAILURE() << "NaN is an input error, not a topology error";
  } catch (const ricci::InvalidInputError& e) {
    EXPECT_EQ(std::string(e.what()), "x.off: vertex 1 has a non-finite coordinate (nan, 0, 0)");
  }
  EXPECT_THROW((void)ricci::build_mesh(ricci::PolygonSoup{}), ricci::TopologyError);
}

double cross2(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

TEST(TriangulatePolygon, ConcavePolygonStaysInsideItsOutline) {
  // An L whose first corner sees no other corner across the notch: a fan from it would fold.
  const std::vector<Eigen::Vector3d> l_shape = {{2, 0, 0}, {2, 1, 0}, {1, 1, 0},
                                                {1, 2, 0}, {0, 2, 0}, {0, 0, 0}};
  const auto triangles = ricci::triangulate_polygon(l_shape);
  ASSERT_EQ(triangles.size(), 4u);
  double area = 0;
  for (const auto& t : triangles) {
    const double doubled = cross2(l_shape[t[0]], l_shape[t[1]], l_shape[t[2]]);
    EXPECT_GT(doubled, 0) << "a folded triangle";
    area += doubled / 2;
  }
  EXPECT_NEAR(area, 3.0, 1e-14);
}

TEST(TriangulatePolygon, NonPlanarPolygonUsesItsBestFitPlaneAndKeepsWinding) {
  std::vector<Eigen::Vector3d> hexagon;
  for (int k = 0; k < 6; ++k)
    hexagon.emplace_back(std::cos(k * M_PI / 3), std::sin(k * M_PI / 3), 0.1 * (k % 2));
  const Eigen::AngleAxisd tilt(0.7, Eigen::Vector3d(1, 2, 3).normalized());
  for (auto& p : hexagon) p = tilt * p;
  const Eigen::Vector3d up = tilt * Eigen::Vector3d::UnitZ();
  const auto triangles = ricci::triangulate_polygon(hexagon);
  ASSERT_EQ(triangles.size(), 4u);
  for (const auto& t : triangles)
    EXPECT_GT((hexagon[t[1]] - hexagon[t[0]]).cross(hexagon[t[2]] - hexagon[t[0]]).dot(up), 0);
}

TEST(TriangulatePolygon, VetoedDiagonalsAreAvoided) {
  const std::vector<Eigen::Vector3d> square = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  auto forbid_02 = [](int i, int j) { return !((i == 0 && j == 2) || (i == 2 && j == 0)); };
  for (const auto& t : ricci::triangulate_polygon(square, forbid_02)) {
    const bool has0 = std::count(t.begin(), t.end(), 0) > 0;
    const bool has2 = std::count(t.begin(), t.end(), 2) > 0;
    EXPECT_FALSE(has0 && has2);
  }
}

}  // namespace

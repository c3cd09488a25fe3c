// diagnose() on procedural soups of known topology: chi = V - E + F = 2c - 2g - b, boundary
// loops, manifoldness, orientability, defects, and invariance under scaling.
#include <gtest/gtest.h>

#include "procedural_soups.h"
#include "ricci/mesh/diagnose.h"

namespace {

using ricci::diagnose;
using ricci::MeshProblemKind;
using namespace ricci_test;

void expect_clean(const ricci::MeshDiagnosis& d) {
  EXPECT_TRUE(d.edge_manifold);
  EXPECT_TRUE(d.vertex_manifold);
  EXPECT_TRUE(d.orientable);
  EXPECT_TRUE(d.clean_manifold());
  EXPECT_TRUE(d.problems.empty()) << d.problems.front().message;
}

MeshProblemKind first_kind(const ricci::MeshDiagnosis& d) {
  EXPECT_FALSE(d.problems.empty());
  return d.problems.empty() ? MeshProblemKind::no_faces : d.problems.front().kind;
}

TEST(Diagnose, TetrahedronIsASphere) {
  const auto d = diagnose(tetrahedron());
  EXPECT_EQ(d.vertices, 4);
  EXPECT_EQ(d.edges, 6);
  EXPECT_EQ(d.faces, 4);
  EXPECT_EQ(d.euler_characteristic, 2);
  EXPECT_EQ(d.genus, 0);
  EXPECT_EQ(d.components, 1);
  EXPECT_EQ(d.boundary_loops, 0);
  EXPECT_TRUE(d.consistently_oriented);
  EXPECT_DOUBLE_EQ(d.bbox_diagonal, std::sqrt(3.0));
  EXPECT_NEAR(d.min_angle_deg, 45.0, 1e-12);
  expect_clean(d);
}

TEST(Diagnose, TorusGridHasGenusOneAsTrianglesOrQuads) {
  for (bool quads : {false, true}) {
    const auto d = diagnose(torus(12, 7, quads));
    EXPECT_EQ(d.vertices, 84);
    EXPECT_EQ(d.faces, quads ? 84 : 168);
    EXPECT_EQ(d.edges, quads ? 168 : 252);
    EXPECT_EQ(d.non_triangle_faces, quads ? 84 : 0);
    EXPECT_EQ(d.euler_characteristic, 0);
    EXPECT_EQ(d.genus, 1);
    EXPECT_EQ(d.boundary_loops, 0);
    expect_clean(d);
  }
}

TEST(Diagnose, DiskAndAnnulusBoundaries) {
  const auto disk_d = diagnose(disk(5, 4));
  EXPECT_EQ(disk_d.boundary_loops, 1);
  EXPECT_EQ(disk_d.boundary_edges, 18);
  EXPECT_EQ(disk_d.euler_characteristic, 1);
  EXPECT_EQ(disk_d.genus, 0);
  expect_clean(disk_d);
  auto annulus = torus(10, 6);  // drop one ring of faces: a cylinder with 2 boundary loops
  annulus.faces.erase(annulus.faces.begin(), annulus.faces.begin() + 12);
  const auto d = diagnose(annulus);
  EXPECT_EQ(d.boundary_loops, 2);
  EXPECT_EQ(d.genus, 0);
  expect_clean(d);
}

TEST(Diagnose, MobiusStripAndKleinBottleAreNonOrientable) {
  const auto strip = diagnose(mobius(8));
  EXPECT_TRUE(strip.edge_manifold && strip.vertex_manifold);
  EXPECT_FALSE(strip.orientable);
  EXPECT_EQ(strip.boundary_loops, 1);  // the Mobius strip's boundary is one circle
  EXPECT_EQ(strip.euler_characteristic, 0);
  EXPECT_EQ(first_kind(strip), MeshProblemKind::non_orientable);
  EXPECT_NE(strip.problems.front().message.find("orientation conflict at edge ("),
            std::string::npos);
  EXPECT_FALSE(strip.clean_manifold());
  const auto klein = diagnose(torus(10, 6, false, true));
  EXPECT_FALSE(klein.orientable);
  EXPECT_EQ(klein.boundary_loops, 0);
  EXPECT_EQ(klein.euler_characteristic, 0);
}

TEST(Diagnose, TwoTetrahedraAreTwoComponents) {
  auto soup = tetrahedron();
  append(soup, tetrahedron(), {5, 0, 0});
  const auto d = diagnose(soup);
  EXPECT_EQ(d.components, 2);
  EXPECT_EQ(d.euler_characteristic, 4);
  EXPECT_EQ(d.genus, 0);
  EXPECT_TRUE(d.clean_manifold());  // INDEX.md's column allows several components
  EXPECT_EQ(first_kind(d), MeshProblemKind::several_components);
  EXPECT_EQ(d.problems.front().message, "2 connected components (vertex counts 4, 4)");
}

TEST(Diagnose, BowtieVertexIsPinched) {
  auto soup = tetrahedron();
  append(soup, tetrahedron(), {-1, -1, -1});
  for (auto& face : soup.faces)
    for (int& v : face)
      if (v == 4) v = 0;  // the second tetrahedron's corner 4 becomes vertex 0: one pinch point
  const auto d = diagnose(soup);
  EXPECT_TRUE(d.edge_manifold);
  EXPECT_FALSE(d.vertex_manifold);
  EXPECT_EQ(d.non_manifold_vertices, 1);
  EXPECT_EQ(d.unreferenced_vertices, 1);
  EXPECT_EQ(d.components, 1);
  EXPECT_EQ(d.euler_characteristic, 3);  // 7 - 12 + 8
  EXPECT_EQ(d.genus, -0.5);              // not a manifold: the formula gives a half-integer
  EXPECT_EQ(first_kind(d), MeshProblemKind::non_manifold_vertex);
  EXPECT_EQ(d.problems.front().message, "vertex 0 is pinched: its faces form 2 fans");
}

TEST(Diagnose, FinEdgeIsNonManifold) {
  auto soup = disk(1, 1);  // faces (0 2 3) (0 3 1)... plus a fin on edge (0, 3)
  soup.positions.emplace_back(0.5, 0.5, 1.0);
  soup.faces.push_back({0, 3, 4});
  const auto d = diagnose(soup);
  EXPECT_FALSE(d.edge_manifold);
  EXPECT_EQ(d.non_manifold_edges, 1);
  EXPECT_EQ(first_kind(d), MeshProblemKind::non_manifold_edge);
  EXPECT_EQ(d.problems.front().message, "edge (0, 3) is shared by 3 faces (faces 0, 1, 2)");
  EXPECT_FALSE(d.clean_manifold());
}

TEST(Diagnose, InconsistentOrientationIsStillOrientable) {
  auto soup = torus(8, 5);
  std::reverse(soup.faces[3].begin(), soup.faces[3].end());
  const auto d = diagnose(soup);
  EXPECT_FALSE(d.consistently_oriented);
  expect_clean(d);  // build_mesh() flips the face back
}

TEST(Diagnose, DegenerateFacesByRepeatedIndexOrCollinearCorners) {
  auto soup = disk(2, 2);
  soup.positions.emplace_back(0.25, 0.0, 0.0);  // on the segment from vertex 0 to vertex 3
  soup.faces.push_back({0, 9, 3});
  soup.faces.push_back({1, 1, 2});
  soup.face_lines.assign(soup.faces.size(), 0);
  soup.face_lines[9] = 42;
  const auto d = diagnose(soup);
  EXPECT_EQ(d.degenerate_faces, 2);
  EXPECT_EQ(first_kind(d), MeshProblemKind::repeated_index);
  EXPECT_EQ(d.problems.front().message,
            "face 9 (line 42) is degenerate: it repeats a vertex index");
  EXPECT_EQ(d.problems.back().kind, MeshProblemKind::zero_area);
  EXPECT_EQ(d.problems.back().message, "face 8 has zero area");
}

TEST(Diagnose, TinyWellShapedTrianglesAreNotDegenerate) {
  auto soup = tetrahedron();
  for (auto& p : soup.positions) p *= 1e-9;  // far below 1e-12 of any bounding box around it
  append(soup, tetrahedron(), {1e3, 0, 0});
  const auto d = diagnose(soup);
  EXPECT_EQ(d.degenerate_faces, 0);
  EXPECT_NEAR(d.min_angle_deg, 45.0, 1e-9);
}

TEST(Diagnose, NonFiniteCoordinatesMatterOnlyWhenReferenced) {
  auto soup = tetrahedron();
  soup.positions.emplace_back(NAN, 0, 0);
  auto d = diagnose(soup);
  EXPECT_EQ(d.non_finite_vertices, 1);
  EXPECT_EQ(d.unreferenced_vertices, 1);
  EXPECT_DOUBLE_EQ(d.bbox_diagonal, std::sqrt(3.0));
  expect_clean(d);
  soup.positions[2].z() = INFINITY;
  d = diagnose(soup);
  EXPECT_EQ(first_kind(d), MeshProblemKind::non_finite_coordinate);
  EXPECT_EQ(d.problems.front().message, "vertex 2 has a non-finite coordinate (0, 1, inf)");
}

TEST(Diagnose, DuplicatesAndBadFaces) {
  auto soup = tetrahedron();
  soup.positions.push_back(soup.positions[1]);
  soup.positions.push_back(soup.positions[1]);
  soup.faces.push_back({3, 1, 2});  // the same vertex set as face 2
  soup.faces.push_back({0, 1, 17});
  soup.faces.push_back({0, 1});
  const auto d = diagnose(soup);
  EXPECT_EQ(d.duplicate_vertices, 2);
  EXPECT_EQ(d.duplicate_faces, 1);
  EXPECT_EQ(d.bad_faces, 2);
  EXPECT_EQ(first_kind(d), MeshProblemKind::bad_face);
  EXPECT_NE(std::find_if(d.problems.begin(), d.problems.end(),
                         [](const ricci::MeshProblem& p) {
                           return p.message == "face 4 has the same vertices as face 2";
                         }),
            d.problems.end());
}

TEST(Diagnose, EmptySoupHasNoFacesProblem) {
  const auto d = diagnose(ricci::PolygonSoup{});
  EXPECT_EQ(first_kind(d), MeshProblemKind::no_faces);
  EXPECT_FALSE(d.clean_manifold());
}

TEST(Diagnose, InvariantUnderScaling) {
  const auto base = diagnose(torus(9, 5));
  for (double scale : {1e-8, 1e8}) {
    auto soup = torus(9, 5);
    for (auto& p : soup.positions) p *= scale;
    const auto d = diagnose(soup);
    EXPECT_EQ(d.edges, base.edges);
    EXPECT_EQ(d.genus, base.genus);
    EXPECT_EQ(d.degenerate_faces, 0);
    EXPECT_NEAR(d.bbox_diagonal, scale * base.bbox_diagonal, 1e-12 * scale * base.bbox_diagonal);
    EXPECT_NEAR(d.min_angle_deg, base.min_angle_deg, 1e-9);
  }
}

}  // namespace

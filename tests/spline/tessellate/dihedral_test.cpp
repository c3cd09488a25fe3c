// dihedral_angles: the angle between the normals of the two triangles at every interior edge.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "ricci/mesh/errors.h"
#include "spline/tessellate/dihedral.h"

namespace spline {
namespace {

using Triangles = std::vector<std::array<int, 3>>;

// Two triangles over the unit square's diagonal (0, 2), the second one's far corner lifted to
// height z: the hinge opens by atan(z sqrt 2) (the corner is 1 / sqrt 2 from the diagonal).
Eigen::MatrixX3d hinge(double z) {
  Eigen::MatrixX3d p(4, 3);
  p << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, z;
  return p;
}

TEST(DihedralAngles, FlatPairIsZeroAndABentPairIsItsAngle) {
  const Triangles pair = {{0, 1, 2}, {0, 2, 3}};
  const DihedralReport flat = dihedral_angles(pair, hinge(0.0));
  EXPECT_EQ(flat.edges, 1);
  EXPECT_NEAR(flat.max_deg, 0.0, 1e-12);
  const double z = 1.0 / std::sqrt(2.0);
  const DihedralReport bent = dihedral_angles(pair, hinge(z));
  EXPECT_NEAR(bent.max_deg, 45.0, 1e-9);
  EXPECT_EQ(bent.over_60_deg, 0);
}

TEST(DihedralAngles, TriangleFoldedBackCountsAsAFold) {
  // The second triangle lies on top of the first, wound the other way: the surface doubles back
  // across edge 0-1 and the normals are opposite.
  Eigen::MatrixX3d p(4, 3);
  p << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.5, 0.4, 0;
  const DihedralReport folded = dihedral_angles({{0, 1, 2}, {1, 0, 3}}, p);
  EXPECT_NEAR(folded.max_deg, 180.0, 1e-9);
  EXPECT_EQ(folded.over_90_deg, 1);
  EXPECT_EQ(folded.over_60_deg, 1);
}

TEST(DihedralAngles, BoundaryNonManifoldAndDegenerateEdgesAreLeftOut) {
  Eigen::MatrixX3d p(5, 3);
  p << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1;
  // Edge 0-1 in three triangles (non-manifold), the rest boundary edges.
  const DihedralReport three = dihedral_angles({{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}, p);
  EXPECT_EQ(three.edges, 0);
  // A repeated corner makes a zero-area triangle: its edges are not measured.
  const DihedralReport degenerate = dihedral_angles({{0, 1, 2}, {1, 0, 0}}, p);
  EXPECT_EQ(degenerate.edges, 0);
}

TEST(DihedralAngles, PercentilesOfAClosedCube) {
  // A cube of 12 triangles: 6 diagonals at 0 degrees, 12 cube edges at 90.
  Eigen::MatrixX3d p(8, 3);
  for (int i = 0; i < 8; ++i) p.row(i) << (i & 1), (i >> 1 & 1), (i >> 2 & 1);
  const Triangles cube = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                          {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  const DihedralReport r = dihedral_angles(cube, p);
  EXPECT_EQ(r.edges, 18);
  EXPECT_NEAR(r.max_deg, 90.0, 1e-9);
  EXPECT_NEAR(r.median_deg, 90.0, 1e-9);
  EXPECT_EQ(r.over_60_deg, 12);
  EXPECT_EQ(r.over_90_deg, 0);
}

// A strip of hinges folded shut, numbered so that neither triangle order nor vertex order
// follows the strip: every fold edge is listed once, by (smaller, larger) vertex, ascending.
TEST(DihedralAngles, FoldEdgesAreListedInVertexOrder) {
  const int hinges = 40;
  std::vector<int> label(4 * hinges);
  for (int i = 0; i < 4 * hinges; ++i) label[i] = (37 * i + 11) % (4 * hinges);
  Eigen::MatrixX3d p(4 * hinges, 3);
  Triangles triangles;
  std::vector<std::array<int, 2>> expected;
  for (int h = hinges - 1; h >= 0; --h) {
    const double x = 3.0 * h;
    const int a = label[4 * h], b = label[4 * h + 1], c = label[4 * h + 2], d = label[4 * h + 3];
    // Hinge along a-b; c and d on the same side: the second triangle folded back onto the first.
    p.row(a) << x, 0, 0;
    p.row(b) << x + 1, 0, 0;
    p.row(c) << x, 1, 0;
    p.row(d) << x + 0.5, 0.4, 0;
    triangles.push_back({a, b, c});
    triangles.push_back({b, a, d});
    expected.push_back({std::min(a, b), std::max(a, b)});
  }
  std::sort(expected.begin(), expected.end());
  const DihedralReport r = dihedral_angles(triangles, p);
  EXPECT_EQ(r.edges, hinges);
  EXPECT_EQ(r.over_90_deg, hinges);
  ASSERT_EQ(r.fold_edges.size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    EXPECT_EQ(r.fold_edges[k][0], expected[k][0]);
    EXPECT_EQ(r.fold_edges[k][1], expected[k][1]);
  }
}

// Five hinges folded back along the x axis at x = 3h (h = 0..4): the first one's positions on a
// patch, the others' fold midpoints 3.5, 6.5, 9.5 and 12.5 from a cone at the origin.
TEST(FoldPlaces, SortsFoldsByPatchAndDistanceFromTheCone) {
  const int hinges = 5;
  Eigen::MatrixX3d p(4 * hinges, 3);
  Triangles triangles;
  std::vector<char> on_patch(4 * hinges, 0);
  for (int h = 0; h < hinges; ++h) {
    const double x = 3.0 * h;
    p.row(4 * h) << x, 0, 0;
    p.row(4 * h + 1) << x + 1, 0, 0;
    p.row(4 * h + 2) << x, 1, 0;
    p.row(4 * h + 3) << x + 0.5, 0.4, 0;
    triangles.push_back({4 * h, 4 * h + 1, 4 * h + 2});
    triangles.push_back({4 * h + 1, 4 * h, 4 * h + 3});
  }
  for (int k = 0; k < 4; ++k) on_patch[static_cast<std::size_t>(k)] = 1;
  const DihedralReport r = dihedral_angles(triangles, p);
  ASSERT_EQ(r.over_90_deg, hinges);
  const FoldPlaces places = fold_places(r.fold_edges, p, on_patch, Eigen::Vector3d::Zero(), 7.0);
  EXPECT_EQ(places.on_patches, 1);
  EXPECT_EQ(places.near_cone, 2);  // 3.5 and 6.5
  EXPECT_EQ(places.elsewhere, 2);  // 9.5 and 12.5
  EXPECT_NEAR(places.median_cone_distance, 9.5, 1e-12);
  // One end on a patch is not enough: the fold is the spline's.
  on_patch[0] = 0;
  on_patch[4] = 1;
  const FoldPlaces moved = fold_places(r.fold_edges, p, on_patch, Eigen::Vector3d::Zero(), 7.0);
  EXPECT_EQ(moved.on_patches, 0);
  EXPECT_EQ(moved.near_cone, 3);
  EXPECT_THROW((void)fold_places(r.fold_edges, p, std::vector<char>(3, 0),
                                 Eigen::Vector3d::Zero(), 1.0),
               ricci::InvalidInputError);
  EXPECT_THROW((void)fold_places(r.fold_edges, p, on_patch, Eigen::Vector3d::Zero(), -1.0),
               ricci::InvalidInputError);
}

}  // namespace
}  // namespace spline

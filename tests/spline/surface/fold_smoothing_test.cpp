// The fold rounds' smoothing floor: the raised level on the folded faces and their rings, then
// a taper with no step larger than its factor between edge neighbours, and nothing far away.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/primitives.h"
#include "spline/surface/fold_smoothing.h"

namespace spline {
namespace {

TEST(FoldSmoothing, RingsCountEdgeNeighbourStepsFromTheFlaggedFaces) {
  const ricci::Mesh mesh = ricci::make_icosphere(3);
  std::vector<char> flagged(mesh.n_faces(), 0);
  flagged[0] = 1;
  const std::vector<int> ring = rings_from_faces(mesh, flagged, 4);
  EXPECT_EQ(ring[0], 0);
  int ones = 0;
  for (auto g : mesh.ff_range(mesh.face_handle(0))) {
    EXPECT_EQ(ring[static_cast<std::size_t>(g.idx())], 1);
    ++ones;
  }
  EXPECT_EQ(ones, 3);
  // Every face's ring is one more than its nearest neighbour's (or -1 past the limit).
  for (auto f : mesh.faces()) {
    const int r = ring[static_cast<std::size_t>(f.idx())];
    if (r == 0) continue;
    int nearest = 1 << 30;
    for (auto g : mesh.ff_range(f)) {
      const int rg = ring[static_cast<std::size_t>(g.idx())];
      if (rg >= 0) nearest = std::min(nearest, rg);
    }
    if (r < 0) {
      EXPECT_TRUE(nearest == 4 || nearest == 1 << 30);
    } else {
      EXPECT_EQ(r, nearest + 1);
    }
  }
}

TEST(FoldSmoothing, FloorTapersWithoutAStepAndVanishesFarAway) {
  const ricci::Mesh mesh = ricci::make_icosphere(3);  // 1280 faces
  std::vector<char> folded(mesh.n_faces(), 0);
  folded[7] = 1;
  FoldSmoothingOptions options;
  options.level = 0.03;
  options.taper_rings = 3;
  const std::vector<double> floor = fold_smoothing_floor(mesh, folded, options);
  const std::vector<int> ring = rings_from_faces(mesh, folded, 64);
  int raised = 0, tapered = 0, zero = 0;
  for (auto f : mesh.faces()) {
    const auto i = static_cast<std::size_t>(f.idx());
    const int r = ring[i];
    if (r <= options.rings) {
      EXPECT_DOUBLE_EQ(floor[i], options.level);
      ++raised;
    } else if (r <= options.rings + options.taper_rings) {
      EXPECT_NEAR(floor[i], options.level * std::pow(options.taper, r - options.rings), 1e-15);
      ++tapered;
    } else {
      EXPECT_EQ(floor[i], 0.0);
      ++zero;
    }
    // Between raised neighbours the floor changes by at most the taper's factor: no step.
    for (auto g : mesh.ff_range(f)) {
      const double a = floor[i], b = floor[static_cast<std::size_t>(g.idx())];
      if (a > 0.0 && b > 0.0) {
        EXPECT_LE(std::max(a, b) / std::min(a, b), 1.0 / options.taper + 1e-12);
      }
    }
  }
  EXPECT_GT(raised, 0);
  EXPECT_GT(tapered, raised);
  EXPECT_GT(zero, tapered);

  // Without a taper the floor is the old step: level inside, 0 outside.
  options.taper_rings = 0;
  const std::vector<double> step = fold_smoothing_floor(mesh, folded, options);
  for (std::size_t i = 0; i < step.size(); ++i)
    EXPECT_EQ(step[i], ring[i] <= options.rings ? options.level : 0.0);
}

TEST(FoldSmoothing, MeshFoldPointsAreTheEdgesTurningOverNinetyDegrees) {
  // A regular tetrahedron's face normals differ by 180 - 70.53 = 109.47 degrees at every edge;
  // a finely sampled sphere turns by a few degrees per edge.
  const ricci::Mesh tetrahedron = ricci::make_tetrahedron();
  const std::vector<Eigen::Vector3d> folds = mesh_fold_points(tetrahedron);
  ASSERT_EQ(folds.size(), 6u);
  for (auto e : tetrahedron.edges()) {
    const Eigen::Vector3d mid = 0.5 * (ricci::to_eigen(tetrahedron.point(e.v0())) +
                                       ricci::to_eigen(tetrahedron.point(e.v1())));
    EXPECT_TRUE(all_within({mid}, folds, 1e-12));
  }
  EXPECT_TRUE(mesh_fold_points(ricci::make_icosphere(2)).empty());

  EXPECT_TRUE(all_within({}, folds, 0.0));
  EXPECT_FALSE(all_within({Eigen::Vector3d(10.0, 0.0, 0.0)}, folds, 1.0));
  EXPECT_FALSE(all_within({folds[0]}, {}, 1.0));
}

TEST(FoldSmoothing, BadInputThrows) {
  const ricci::Mesh mesh = ricci::make_icosphere(1);
  const std::vector<char> wrong_size(mesh.n_faces() + 1, 0);
  EXPECT_THROW((void)fold_smoothing_floor(mesh, wrong_size), ricci::InvalidInputError);
  EXPECT_THROW((void)rings_from_faces(mesh, wrong_size, 2), ricci::InvalidInputError);
  const std::vector<char> flags(mesh.n_faces(), 0);
  EXPECT_THROW((void)rings_from_faces(mesh, flags, -1), ricci::InvalidInputError);
  FoldSmoothingOptions bad;
  bad.taper = 0.0;
  EXPECT_THROW((void)fold_smoothing_floor(mesh, flags, bad), ricci::InvalidInputError);
  bad = {};
  bad.level = 0.0;
  EXPECT_THROW((void)fold_smoothing_floor(mesh, flags, bad), ricci::InvalidInputError);
}

}  // namespace
}  // namespace spline

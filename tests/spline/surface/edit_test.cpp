// Editing: the support relation is the one evaluation uses (reaching_faces), moving control
// points changes the surface only on the moved functions' supports (bit for bit elsewhere), a
// region move displaces the surface at its centre by about the displacement and leaves functions
// whose support is farther than the radius alone, and the report names the touched fills.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <set>

#include "ricci/mesh/errors.h"
#include "spline/surface/edit.h"
#include "spline/surface/surface_fixtures.h"

namespace spline {
namespace {

using testing::small_surface;

bool same_position(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0;
}

const Eigen::Vector3d kBarycentrics[] = {
    {1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0}, {0.7, 0.2, 0.1}, {1.0, 0.0, 0.0}, {0.0, 0.5, 0.5}};

// Faces outside `affected` evaluate bit for bit as before (positions and derivatives); returns
// how many points inside it moved.
int expect_unchanged_outside(const SplineSurface& before, const SplineSurface& after,
                             const std::vector<int>& affected) {
  const std::set<int> inside(affected.begin(), affected.end());
  int moved = 0;
  for (int face : before.spline.space->domain_faces()) {
    for (const Eigen::Vector3d& b : kBarycentrics) {
      const SurfaceJet x = before.spline.evaluate({face, b});
      const SurfaceJet y = after.spline.evaluate({face, b});
      const bool same = same_position(x.position, y.position) && same_position(x.du, y.du) &&
                        same_position(x.dv, y.dv) && same_position(x.duu, y.duu);
      if (inside.count(face)) {
        moved += !same;
      } else {
        EXPECT_TRUE(same) << "face " << face << " outside the supports changed";
      }
    }
  }
  return moved;
}

TEST(Edit, SupportIsWhereEvaluationReaches) {
  const SplineSurface& surface = small_surface("genus2.off");
  const ManifoldSplineSpace& space = *surface.spline.space;
  std::map<int, std::set<int>> reached_from;  // face I -> faces g whose evaluation uses I
  for (int g : space.domain_faces()) {
    for (int face : space.reaching_faces(g)) reached_from[face].insert(g);
  }
  for (int face : space.domain_faces()) {
    const std::vector<int> support = function_support_faces(surface, face);
    EXPECT_EQ(std::set<int>(support.begin(), support.end()), reached_from[face]) << face;
  }
  EXPECT_THROW((void)function_support_faces(surface, -1), ricci::InvalidInputError);
}

TEST(Edit, MovingOneControlPointChangesOnlyItsSupport) {
  const SplineSurface& before = small_surface("genus2.off");
  SplineSurface after = before;
  const int function = before.spline.space->function_count() / 2 + 3;
  const EditReport report = move_control_points(after, {function}, {{0.0, 0.05, -0.02}});
  EXPECT_EQ(report.moved_functions, std::vector<int>{function});
  EXPECT_DOUBLE_EQ(report.max_displacement, Eigen::Vector3d(0.0, 0.05, -0.02).norm());
  const int face =
      before.spline.space->domain_faces()[function / before.spline.space->functions_per_face()];
  EXPECT_EQ(report.affected_faces, function_support_faces(before, face));
  EXPECT_GT(expect_unchanged_outside(before, after, report.affected_faces), 0);
  // The surface moves by N_f(u) times the displacement.
  const DomainPoint centre{face, Eigen::Vector3d::Constant(1.0 / 3.0)};
  double value = 0.0;
  for (const auto& s : before.spline.space->evaluate_basis(centre)) {
    if (s.function == function) value = s.jet.value;
  }
  const Eigen::Vector3d delta =
      after.spline.evaluate(centre).position - before.spline.evaluate(centre).position;
  EXPECT_NEAR((delta - value * Eigen::Vector3d(0.0, 0.05, -0.02)).norm(), 0.0, 1e-14);
}

TEST(Edit, BadIndicesAndDisplacementsAreRefused) {
  SplineSurface surface = small_surface("genus1.off", 200);
  const Eigen::MatrixX3d points = surface.spline.control_points;
  const int n = surface.spline.space->function_count();
  EXPECT_THROW((void)move_control_points(surface, {n}, {Eigen::Vector3d::Zero()}),
               ricci::InvalidInputError);
  EXPECT_THROW((void)move_control_points(surface, {0, 1}, {Eigen::Vector3d::UnitX()}),
               ricci::InvalidInputError);
  EXPECT_THROW((void)move_control_points(surface, {0}, {Eigen::Vector3d::Constant(std::nan(""))}),
               ricci::InvalidInputError);
  EXPECT_THROW((void)move_region(surface, Eigen::Vector3d::Zero(), 0.0, Eigen::Vector3d::UnitX()),
               ricci::InvalidInputError);
  EXPECT_THROW(
      (void)move_region(surface, Eigen::Vector3d::Zero(), std::nan(""), Eigen::Vector3d::UnitX()),
      ricci::InvalidInputError);
  EXPECT_TRUE(surface.spline.control_points == points);  // unchanged by refused edits
}

// The centre of the shown face farthest (in space) from the fills' rims, and that distance.
std::pair<DomainPoint, double> point_far_from_rims(const SplineSurface& surface) {
  std::vector<Eigen::Vector3d> rim_points;
  for (const HoleFill& fill : surface.fills) {
    for (const RimEdge& e : fill.rim.edges) {
      rim_points.push_back(
          surface.spline.evaluate({e.face, rim_edge_barycentric(e, 0.5)}).position);
    }
  }
  std::pair<DomainPoint, double> best{{}, -1.0};
  for (int face : surface.spline.space->domain_faces()) {
    if (surface.skipped_faces[face]) continue;
    const DomainPoint point{face, Eigen::Vector3d::Constant(1.0 / 3.0)};
    const Eigen::Vector3d p = surface.spline.evaluate(point).position;
    double nearest = 1e300;
    for (const Eigen::Vector3d& q : rim_points) nearest = std::min(nearest, (p - q).norm());
    if (nearest > best.second) best = {point, nearest};
  }
  return best;
}

TEST(Edit, RegionMoveIsSmoothAndLocal) {
  const SplineSurface& before = small_surface("genus2.off");
  const auto [point, rim_distance] = point_far_from_rims(before);
  ASSERT_GE(point.face, 0);
  const Eigen::Vector3d centre = before.spline.evaluate(point).position;
  const ricci::Mesh& mesh = before.domain;
  const auto h = mesh.halfedge_handle(mesh.face_handle(point.face));
  const double edge = mesh.calc_edge_length(h);
  const double radius = 2.0 * edge;
  ASSERT_GT(rim_distance, radius + 3.0 * edge);  // the supports reach about an edge further
  const Eigen::Vector3d displacement(0.0, 0.0, 0.5 * edge);
  SplineSurface after = before;
  const EditReport report = move_region(after, centre, radius, displacement);
  ASSERT_FALSE(report.moved_functions.empty());
  EXPECT_TRUE(std::is_sorted(report.moved_functions.begin(), report.moved_functions.end()));
  for (double w : report.weights) {
    EXPECT_GT(w, 0.0);
    EXPECT_LE(w, 1.0);
  }
  EXPECT_LT(report.affected_faces.size(), before.spline.space->domain_face_count() / 2u);
  EXPECT_GT(expect_unchanged_outside(before, after, report.affected_faces), 10);
  // At the centre the weights are near 1 and the basis sums to 1: it moves by about D.
  const Eigen::Vector3d delta =
      after.spline.evaluate(point).position - before.spline.evaluate(point).position;
  EXPECT_LT((delta - displacement).norm(), 0.1 * displacement.norm()) << delta.transpose();
  // Control points of faces whose support's surface is farther than the radius stay.
  const std::set<int> moved(report.moved_functions.begin(), report.moved_functions.end());
  for (int f = 0; f < before.spline.space->function_count(); ++f) {
    if (!moved.count(f)) {
      EXPECT_TRUE(after.spline.control_points.row(f) == before.spline.control_points.row(f));
    }
  }
  // Far from the cone's rim: the fill is not touched; centred on the rim, it is.
  EXPECT_TRUE(report.touched_fills.empty());
  ASSERT_EQ(before.fills.size(), 1u);
  const RimEdge& rim_edge = before.fills[0].rim.edges[0];
  const Eigen::Vector3d on_rim =
      before.spline.evaluate({rim_edge.face, rim_edge_barycentric(rim_edge, 0.5)}).position;
  SplineSurface near_rim = before;
  const EditReport rim_report = move_region(near_rim, on_rim, radius, displacement);
  EXPECT_EQ(rim_report.touched_fills, std::vector<int>{0});
}

TEST(Edit, RegionFarFromTheSurfaceMovesNothing) {
  SplineSurface surface = small_surface("genus1.off", 200);
  const Eigen::MatrixX3d points = surface.spline.control_points;
  const EditReport report =
      move_region(surface, Eigen::Vector3d(100.0, 100.0, 100.0), 1.0, Eigen::Vector3d::UnitX());
  EXPECT_TRUE(report.moved_functions.empty());
  EXPECT_TRUE(report.affected_faces.empty());
  EXPECT_TRUE(surface.spline.control_points == points);
}

}  // namespace
}  // namespace spline

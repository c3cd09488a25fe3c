// Point tracking through Ptolemy flips (ricci/intrinsic/point_tracking.h): on cyclic quads the
// tracked points keep their Euclidean position, through a genus-4 one-cone flow with flips they
// keep their hyperbolic distances, every input vertex lands on its own corner and every tracked
// point maps back to its 3D position.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "ricci/flow/targets.h"
#include "ricci/intrinsic/conformal_flow.h"
#include "ricci/intrinsic/point_tracking.h"
#include "ricci/mesh/arrays.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/primitives.h"
#include "ricci/metric/mesh_tables.h"

namespace {

using ricci::IntrinsicTriangulation;
using ricci::TriangulationPoint;

// Every face's centroid and `random_per_face` random points of it.
std::vector<TriangulationPoint> face_points(const IntrinsicTriangulation& tri,
                                            int random_per_face) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> weight(0.01, 1.0);
  std::vector<TriangulationPoint> points;
  for (int f = 0; f < tri.face_count(); ++f) {
    points.push_back({f, Eigen::Vector3d::Constant(1.0 / 3.0)});
    for (int n = 0; n < random_per_face; ++n) {
      Eigen::Vector3d w(weight(random), weight(random), weight(random));
      points.push_back({f, w / w.sum()});
    }
  }
  return points;
}

// Squared length at u of the edge between corners a and b of a face (corners k and k + 1 are
// joined by the edge of halfedge 3f + k).
double squared_length(const IntrinsicTriangulation& tri, int face, int a, int b,
                      const Eigen::VectorXd& u) {
  const int k = (b == (a + 1) % 3) ? a : b;
  return std::exp(2.0 * tri.log_length_at(tri.edge[static_cast<size_t>(3 * face + k)], u));
}

// Q(c, d) = -2 <x, y> for x = sum c_a p_a, y = sum d_b p_b (-2 <p_a, p_b> = l_ab^2).
double minkowski(const IntrinsicTriangulation& tri, int face, const Eigen::Vector3d& c,
                 const Eigen::Vector3d& d, const Eigen::VectorXd& u) {
  double q = 0;
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3;
    q += (c[a] * d[b] + c[b] * d[a]) * squared_length(tri, face, a, b, u);
  }
  return q;
}

// 2 sinh(d / 2), d the hyperbolic distance between two points of one face given by their
// barycentric coordinates at u: the Minkowski norm of the difference of the unit vectors.
double hyperbolic_chord(const IntrinsicTriangulation& tri, int face, const Eigen::Vector3d& c,
                        const Eigen::Vector3d& d, const Eigen::VectorXd& u) {
  const Eigen::Vector3d e = c / std::sqrt(0.5 * minkowski(tri, face, c, c, u)) -
                            d / std::sqrt(0.5 * minkowski(tri, face, d, d, u));
  return std::sqrt(std::max(0.0, -0.5 * minkowski(tri, face, e, e, u)));
}

TEST(PointTracking, FlipsOfCyclicQuadsKeepEuclideanPositions) {
  // A flat torus of 1 x 0.75 rectangles: every quad is cyclic, its Ptolemy diagonal is the
  // Euclidean one, and the hyperbolic correspondence is the identity of the plane.
  const int nx = 5, ny = 4;
  const double width = 5.0, height = 3.0;
  const ricci::Mesh mesh = ricci::make_flat_torus_grid(nx, ny, width, height);
  const IntrinsicTriangulation initial = ricci::make_intrinsic_triangulation(
      mesh, ricci::flat_torus_edge_lengths(mesh, nx, ny, width, height));
  std::vector<int> log;  // every cell's diagonal
  const double diagonal = std::log(std::hypot(width / nx, height / ny));
  for (int e = 0; e < initial.edge_count(); ++e) {
    if (std::abs(initial.log_length[e] - diagonal) < 1e-12) log.push_back(e);
  }
  ASSERT_EQ(static_cast<int>(log.size()), nx * ny);
  const ricci::IntrinsicCorrespondence map(initial, log);
  EXPECT_EQ(map.flips(), nx * ny);

  const auto planar = [&](int v) {
    return Eigen::Vector2d((v / ny) * width / nx, (v % ny) * height / ny);
  };
  const auto wrapped = [&](Eigen::Vector2d d) {
    d.x() -= width * std::round(d.x() / width);
    d.y() -= height * std::round(d.y() / height);
    return d;
  };
  // The point's plane position, its face's corners unwrapped around corner 0.
  const auto position = [&](const IntrinsicTriangulation& tri, const TriangulationPoint& p) {
    const Eigen::Vector2d origin = planar(tri.tail[static_cast<size_t>(3 * p.face)]);
    Eigen::Vector2d x = origin;
    for (int k = 1; k < 3; ++k) {
      x += p.weights[k] * wrapped(planar(tri.tail[static_cast<size_t>(3 * p.face + k)]) - origin);
    }
    return x;
  };
  const std::vector<TriangulationPoint> points = face_points(initial, 3);
  const std::vector<TriangulationPoint> moved = map.to_final(points);
  int changed_face = 0;
  for (size_t n = 0; n < points.size(); ++n) {
    const Eigen::Vector2d before = position(initial, points[n]);
    const Eigen::Vector2d after = position(map.final_triangulation(), moved[n]);
    EXPECT_LT(wrapped(after - before).norm(), 1e-12) << "point " << n;
    changed_face += moved[n].weights.isApprox(points[n].weights, 1e-6) ? 0 : 1;
  }
  EXPECT_GT(changed_face, static_cast<int>(points.size()) / 2);  // the flips did move them
}

TEST(PointTracking, GenusFourFlowKeepsEveryPointAndVertex) {
  const ricci::Mesh mesh = ricci::make_genus_slab(4, 2, 4);
  const IntrinsicTriangulation initial =
      ricci::make_intrinsic_triangulation(mesh, ricci::mesh_edge_lengths(mesh));
  const ricci::IntrinsicFlowResult r =
      ricci::intrinsic_conformal_flow(initial, ricci::single_cone_target(mesh, 0).curvature);
  ASSERT_TRUE(r.converged() || r.max_error < 1e-8) << r.message;
  ASSERT_GT(r.flips, 100);
  ASSERT_EQ(static_cast<int>(r.flip_log.size()), r.flips);

  const ricci::IntrinsicCorrespondence map(initial, r.flip_log);
  const IntrinsicTriangulation& final_tri = map.final_triangulation();
  EXPECT_EQ(final_tri.tail, r.triangulation.tail);  // the replay is the flow's triangulation
  EXPECT_EQ(final_tri.edge, r.triangulation.edge);
  EXPECT_TRUE(final_tri.log_length == r.triangulation.log_length);

  std::vector<TriangulationPoint> points = face_points(initial, 4);
  const size_t first_vertex = points.size();
  for (const TriangulationPoint& p : ricci::vertex_points(initial)) points.push_back(p);
  const std::vector<TriangulationPoint> on_final = map.to_final(points);
  const std::vector<TriangulationPoint> back = map.to_initial(on_final);

  // Every tracked point maps back to its 3D position.
  const Eigen::MatrixX3d V = ricci::to_arrays(mesh).V;
  const double diagonal = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  double worst = 0;
  for (size_t n = 0; n < points.size(); ++n) {
    const Eigen::Vector3d x = ricci::point_position(initial, V, points[n]);
    worst = std::max(worst, (ricci::point_position(initial, V, back[n]) - x).norm() / diagonal);
  }
  EXPECT_LT(worst, 1e-9);

  // Every input vertex lands on a corner of itself with weight 1.
  for (size_t n = first_vertex; n < points.size(); ++n) {
    const int v = static_cast<int>(n - first_vertex);
    Eigen::Index k = 0;
    EXPECT_NEAR(on_final[n].weights.maxCoeff(&k), 1.0, 1e-12) << "vertex " << v;
    EXPECT_EQ(final_tri.tail[static_cast<size_t>(3 * on_final[n].face + k)], v);
  }

  // Hyperbolic distances between points sharing a face before and after, at u = 0 on the
  // initial triangulation and at the flow's u on the final one (barycentric_at), agree.
  int pairs = 0, moved_pairs = 0;
  for (size_t a = 0; a < first_vertex; ++a) {
    for (size_t b = a + 1; b < first_vertex && points[b].face == points[a].face; ++b) {
      if (on_final[b].face != on_final[a].face) continue;
      const Eigen::VectorXd zero = Eigen::VectorXd::Zero(initial.vertex_count);
      const double before =
          hyperbolic_chord(initial, points[a].face, points[a].weights, points[b].weights, zero);
      const double after = hyperbolic_chord(
          final_tri, on_final[a].face, ricci::barycentric_at(final_tri, on_final[a], r.u),
          ricci::barycentric_at(final_tri, on_final[b], r.u), r.u);
      EXPECT_NEAR(after, before, 1e-9 * before) << "points " << a << ", " << b;
      ++pairs;
      moved_pairs += on_final[a].weights.isApprox(points[a].weights, 1e-6) ? 0 : 1;
    }
  }
  EXPECT_GT(pairs, 100);
  EXPECT_GT(moved_pairs, 10);  // pairs the flips carried, not only faces no flip touched
}

TEST(PointTracking, BarycentricAtScaleFactorsIsInvertible) {
  const ricci::Mesh mesh = ricci::make_genus_slab(4);
  const IntrinsicTriangulation tri =
      ricci::make_intrinsic_triangulation(mesh, ricci::mesh_edge_lengths(mesh));
  const Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(tri.vertex_count, -3.0, 2.0);
  const TriangulationPoint p{5, Eigen::Vector3d(0.2, 0.3, 0.5)};
  const Eigen::Vector3d b = ricci::barycentric_at(tri, p, u);
  EXPECT_NEAR(b.sum(), 1.0, 1e-15);
  EXPECT_FALSE(b.isApprox(p.weights, 1e-3));  // the scale factors differ at the corners
  const TriangulationPoint q = ricci::point_at_barycentric(tri, p.face, b, u);
  EXPECT_EQ(q.face, p.face);
  EXPECT_LT((q.weights - p.weights).norm(), 1e-15);
}

TEST(PointTracking, RefusesBadFlipsAndPoints) {
  const ricci::Mesh mesh = ricci::make_genus_slab(4);
  const IntrinsicTriangulation tri =
      ricci::make_intrinsic_triangulation(mesh, ricci::mesh_edge_lengths(mesh));
  EXPECT_THROW(ricci::IntrinsicCorrespondence(tri, {tri.edge_count()}), ricci::InvalidInputError);
  const ricci::IntrinsicCorrespondence map(tri, {0, 1});
  EXPECT_THROW((void)map.to_final({{tri.face_count(), Eigen::Vector3d(1, 0, 0)}}),
               ricci::InvalidInputError);
  EXPECT_THROW((void)map.to_initial({{0, Eigen::Vector3d(0, 0, 0)}}), ricci::InvalidInputError);
  EXPECT_THROW((void)ricci::vertex_point(tri, -1), ricci::InvalidInputError);
  const std::vector<TriangulationPoint> corners = ricci::vertex_points(tri);
  for (int v = 0; v < tri.vertex_count; v += 7) {  // both find a corner of v
    const TriangulationPoint p = ricci::vertex_point(tri, v), q = corners[static_cast<size_t>(v)];
    EXPECT_EQ(ricci::point_position(tri, Eigen::MatrixX3d::Identity(tri.vertex_count, 3), p),
              ricci::point_position(tri, Eigen::MatrixX3d::Identity(tri.vertex_count, 3), q));
  }
}

}  // namespace

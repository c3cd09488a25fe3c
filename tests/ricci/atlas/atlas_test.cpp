#include "ricci/atlas/atlas.h"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include "ricci/atlas/chart_develop.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/primitives.h"
#include "ricci/topology/test_grids.h"

namespace ricci {
namespace {

/// Facts every atlas must satisfy, whatever the mesh: neighbourhood charts exist and are
/// isometric, positively oriented planar pieces; transitions fit to `tolerance` (relative to the
/// domain diameter) and map corners between charts.
void expect_consistent_atlas(const Mesh& mesh, const Eigen::VectorXd& lengths,
                             const AffineAtlas& atlas, double tolerance) {
  EXPECT_EQ(atlas.uncovered_faces, 0);
  EXPECT_EQ(atlas.layout.flipped_faces, 0);
  EXPECT_LT(atlas.layout.max_relative_length_error, tolerance);
  EXPECT_LT(atlas.max_transition_residual, tolerance * atlas.domain_diameter);
  EXPECT_LT(atlas.max_side_pairing_residual, tolerance * atlas.domain_diameter);
  for (auto f : mesh.faces()) {
    const int c = atlas.chart_of_face_neighbourhood(f.idx());
    if (!atlas.in_domain[f.idx()]) {
      EXPECT_EQ(c, -1);
      continue;
    }
    ASSERT_GE(c, 0) << "face " << f.idx();
    const auto hood = detail::face_neighbourhood(mesh, f.idx(), atlas.in_domain);
    EXPECT_TRUE(detail::holds_as_one_piece(mesh, atlas.charts[c], hood));
    for (int g : hood) {
      const auto p = atlas.face_positions(c, g);
      const Eigen::Vector2d u = p.row(1) - p.row(0), v = p.row(2) - p.row(0);
      EXPECT_GT(u.x() * v.y() - u.y() * v.x(), 0.0);
      const auto hs = face_halfedges(mesh, FaceHandle(g));
      for (int k = 0; k < 3; ++k) {
        const double l = lengths[mesh.edge_handle(hs[k]).idx()];
        EXPECT_NEAR((p.row(k) - p.row((k + 2) % 3)).norm(), l, tolerance * l);
      }
    }
  }
  // Every transition maps its faces' corners from one chart onto the other.
  for (const Transition& t : atlas.transitions) {
    for (int f : t.faces) {
      const auto a = atlas.face_positions(t.chart_a, f), b = atlas.face_positions(t.chart_b, f);
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector2d mapped = atlas.map(a.row(k).transpose(), t.chart_a, t.chart_b, f);
        EXPECT_LT((mapped - b.row(k).transpose()).norm(), tolerance * atlas.domain_diameter);
        const Eigen::Vector2d back = atlas.map(b.row(k).transpose(), t.chart_b, t.chart_a, f);
        EXPECT_LT((back - a.row(k).transpose()).norm(), tolerance * atlas.domain_diameter);
      }
    }
  }
}

/// True when t is an integer combination of the lattice basis (g1, g2).
bool in_lattice(const Eigen::Vector2d& t, const Eigen::Vector2d& g1, const Eigen::Vector2d& g2) {
  Eigen::Matrix2d basis;
  basis << g1, g2;
  const Eigen::Vector2d c = basis.inverse() * t;
  return (c - c.array().round().matrix()).cwiseAbs().maxCoeff() < 1e-9;
}

TEST(Atlas, FlatTorusTransitionsAreTranslationsByPeriods) {
  const int nx = 18, ny = 12;
  const double w = 4.5, h = 2.0;
  const Mesh torus = make_flat_torus_grid(nx, ny, w, h);
  const Eigen::VectorXd lengths = flat_torus_edge_lengths(torus, nx, ny, w, h);
  for (int root : {0, 77}) {
    SCOPED_TRACE("root " + std::to_string(root));
    const AffineAtlas atlas = build_affine_atlas(torus, lengths, VertexHandle(root));
    EXPECT_FALSE(atlas.root_is_cone);
    EXPECT_NEAR(atlas.root_curvature, 0.0, 1e-12);
    EXPECT_TRUE(atlas.polygon.canonical);
    expect_consistent_atlas(torus, lengths, atlas, 1e-12);
    EXPECT_GE(atlas.charts.size(), 3u);  // central + one per loop at least
    // Each side pairing is a deck translation; the loops' two are the periods: shortest loops
    // on this grid are the straight ones, of lengths h and w, perpendicular (the layout's frame
    // is rotated by the seed edge, so compare norms and angles, not coordinates).
    std::vector<Eigen::Vector2d> generators;
    for (const SidePairing& s : atlas.side_pairings) {
      EXPECT_LT(std::abs(s.motion.angle), 1e-12);
      if (s.loop >= 0) generators.push_back(s.motion.translation);
    }
    ASSERT_EQ(generators.size(), 2u);
    std::sort(generators.begin(), generators.end(),
              [](const auto& a, const auto& b) { return a.norm() < b.norm(); });
    EXPECT_NEAR(generators[0].norm(), h, 1e-10);
    EXPECT_NEAR(generators[1].norm(), w, 1e-10);
    EXPECT_NEAR(generators[0].dot(generators[1]), 0.0, 1e-10);
    for (const SidePairing& s : atlas.side_pairings) {
      EXPECT_TRUE(in_lattice(s.motion.translation, generators[0], generators[1]));
      EXPECT_GT(s.motion.translation.norm(), 0.5 * h);  // a cut never pairs a side with itself
    }
    // The loops' holonomies are the two periods too, and commute.
    ASSERT_EQ(atlas.loop_holonomy.size(), 2u);
    std::vector<double> norms;
    for (const auto& m : atlas.loop_holonomy) {
      EXPECT_LT(std::abs(m.angle), 1e-12);
      EXPECT_TRUE(in_lattice(m.translation, generators[0], generators[1]));
      norms.push_back(m.translation.norm());
    }
    std::sort(norms.begin(), norms.end());
    EXPECT_NEAR(norms[0], h, 1e-10);
    EXPECT_NEAR(norms[1], w, 1e-10);
    EXPECT_LT(atlas.relator_holonomy_translation, 1e-12 * atlas.domain_diameter);
    // Charts are developed in the central chart's frame: every transition is a deck translation.
    for (const Transition& t : atlas.transitions) {
      EXPECT_LT(std::abs(t.motion.angle), 1e-12);
      EXPECT_TRUE(in_lattice(t.motion.translation, generators[0], generators[1]))
          << t.motion.translation.transpose();
    }
  }
}

TEST(Atlas, ShearedFlatTorusHolonomyGeneratesTheLattice) {
  const int nx = 15, ny = 10;
  const double w = 3.0, h = 2.0, shear = 1.3;
  const Mesh torus = make_flat_torus_grid(nx, ny, w, h, shear);
  const Eigen::VectorXd lengths = flat_torus_edge_lengths(torus, nx, ny, w, h, shear);
  const AffineAtlas atlas = build_affine_atlas(torus, lengths, VertexHandle(31));
  expect_consistent_atlas(torus, lengths, atlas, 1e-12);
  ASSERT_EQ(atlas.loop_holonomy.size(), 2u);
  const Eigen::Vector2d g1 = atlas.loop_holonomy[0].translation;
  const Eigen::Vector2d g2 = atlas.loop_holonomy[1].translation;
  // A basis of the period lattice has covolume w * h, whatever the shear.
  EXPECT_NEAR(std::abs(g1.x() * g2.y() - g1.y() * g2.x()), w * h, 1e-10);
  for (const Transition& t : atlas.transitions) {
    EXPECT_LT(std::abs(t.motion.angle), 1e-12);
    EXPECT_TRUE(in_lattice(t.motion.translation, g1, g2));
  }
  for (const SidePairing& s : atlas.side_pairings) {
    EXPECT_TRUE(in_lattice(s.motion.translation, g1, g2));
  }
}

TEST(Atlas, PlanarGridWithInteriorRootIsOneSheet) {
  const Mesh grid = test::planar_grid(14, 10, 3.5, 2.5);
  const Eigen::VectorXd lengths = checked_edge_lengths(grid, {});
  const AffineAtlas atlas = build_affine_atlas(grid, lengths, VertexHandle(7 * 15 + 5));
  EXPECT_FALSE(atlas.root_is_cone);
  expect_consistent_atlas(grid, lengths, atlas, 1e-12);
  // Cutting a planar disk along a tree path changes nothing in the plane: all motions are the
  // identity.
  for (const SidePairing& s : atlas.side_pairings) {
    EXPECT_LT(std::abs(s.motion.angle), 1e-12);
    EXPECT_LT(s.motion.translation.norm(), 1e-12);
  }
  for (const Transition& t : atlas.transitions) {
    EXPECT_LT(std::abs(t.motion.angle), 1e-12);
    EXPECT_LT(t.motion.translation.norm(), 1e-12);
  }
}

TEST(Atlas, RigidMotionFitRecoversAMotion) {
  RigidMotion2 m;
  m.angle = 2.5;
  m.translation = Eigen::Vector2d(-3.0, 7.0);
  Eigen::MatrixX2d from(4, 2), to(4, 2);
  from << 0, 0, 1, 0, 0, 2, 3, 1;
  for (int i = 0; i < 4; ++i) to.row(i) = m.apply(from.row(i).transpose()).transpose();
  double residual = 1.0;
  const RigidMotion2 fit = fit_rigid_motion(from, to, &residual);
  EXPECT_NEAR(fit.angle, 2.5, 1e-14);
  EXPECT_LT((fit.translation - m.translation).norm(), 1e-13);
  EXPECT_LT(residual, 1e-13);
  const RigidMotion2 id = m.inverse().after(m);
  EXPECT_NEAR(id.angle, 0.0, 1e-15);
  EXPECT_LT(id.translation.norm(), 1e-14);
}

// A cluster 1e-13 wide at coordinates of size 10 (the faces next to a large cone in a chart of
// the whole domain): its double positions round at 1e-15, a hundredth of its width, so the fit
// on them misses the angle; on offsets known to ~1e-30 (a layout's double-double differences)
// the angle and the residual are exact.
TEST(Atlas, RigidMotionFitOnOffsetsKeepsTheAngleOfATinyCluster) {
  RigidMotion2 m;
  m.angle = 0.7;
  m.translation = Eigen::Vector2d(1.0, -2.0);
  const Eigen::Vector2d base(7.3, -6.1);
  Eigen::MatrixX2d offsets(4, 2);
  offsets << 0, 0, 1, 0, 0.3, 0.8, -0.5, 0.6;
  offsets *= 1e-13;
  const Eigen::Matrix2d r = m.rotation();
  const Eigen::Vector2d to_base = m.apply(base);
  const Eigen::MatrixX2d to_offsets = offsets * r.transpose();
  Eigen::MatrixX2d from(4, 2), to(4, 2);
  for (int i = 0; i < 4; ++i) {
    from.row(i) = base.transpose() + offsets.row(i);
    to.row(i) = to_base.transpose() + to_offsets.row(i);
  }
  double rounded = 0.0, precise = 1.0;
  const RigidMotion2 on_positions = fit_rigid_motion(from, to, &rounded);
  const RigidMotion2 on_offsets = fit_rigid_motion(base, offsets, to_base, to_offsets, &precise);
  EXPECT_GT(std::abs(on_positions.angle - m.angle), 1e-4);  // the premise
  EXPECT_NEAR(on_offsets.angle, m.angle, 1e-12);
  EXPECT_LT((on_offsets.translation - m.translation).norm(), 1e-13);
  EXPECT_LT(precise, 1e-25);
  EXPECT_THROW((void)fit_rigid_motion(base, offsets, to_base, Eigen::MatrixX2d(3, 2)),
               InvalidInputError);
}

// With the angle given (a layout's developed directions), the fit takes the translation and
// the residual from the offsets: exact for the true angle, and the residual shows a wrong one.
TEST(Atlas, RigidMotionFitWithAGivenAngle) {
  RigidMotion2 m;
  m.angle = -2.2;
  m.translation = Eigen::Vector2d(4.0, 0.5);
  const Eigen::Vector2d base(-3.1, 8.4);
  Eigen::MatrixX2d offsets(3, 2);
  offsets << 0, 0, 1, 0.2, 0.4, 0.9;
  const Eigen::MatrixX2d to_offsets = offsets * m.rotation().transpose();
  double residual = 1.0;
  const RigidMotion2 fit = fit_rigid_motion(m.angle, base, offsets, m.apply(base), to_offsets,
                                            &residual);
  EXPECT_EQ(fit.angle, m.angle);
  EXPECT_LT((fit.translation - m.translation).norm(), 1e-13);
  EXPECT_LT(residual, 1e-14);
  (void)fit_rigid_motion(m.angle + 1e-3, base, offsets, m.apply(base), to_offsets, &residual);
  EXPECT_GT(residual, 1e-4);
  EXPECT_THROW((void)fit_rigid_motion(0.0, base, offsets, base, Eigen::MatrixX2d(2, 2)),
               InvalidInputError);
}

TEST(Atlas, QueriesRejectWhatTheChartsDoNotHold) {
  const Mesh torus = make_flat_torus_grid(8, 8, 1.0, 1.0);
  const AffineAtlas atlas =
      build_affine_atlas(torus, flat_torus_edge_lengths(torus, 8, 8, 1.0, 1.0), VertexHandle(0));
  EXPECT_THROW((void)atlas.corner_position(99, 0, 0), InvalidInputError);
  EXPECT_THROW((void)atlas.corner_position(0, 0, 3), InvalidInputError);
  // A loop chart holds only faces near its loop: find a face it lacks.
  const Chart& loop_chart = atlas.charts[1];
  int missing = -1;
  for (auto f : torus.faces()) {
    if (loop_chart.slot(f.idx()) < 0) missing = f.idx();
  }
  ASSERT_GE(missing, 0);
  EXPECT_FALSE(atlas.transition(0, 1, missing).has_value());
  EXPECT_THROW((void)atlas.map(Eigen::Vector2d::Zero(), 0, 1, missing), InvalidInputError);
}

}  // namespace
}  // namespace ricci

// Bezier export: the patches are the spline's polynomial pieces (1e-12 of the diagonal at random
// points of every face), cover every face, and meet with the spline's C^(n-1) continuity across
// the domain's edges. Genus 0-3 bundled models.
#include "spline/surface/bezier.h"

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <random>

#include "ricci/mesh/errors.h"
#include "spline/fit/fit.h"
#include "surface_fixtures.h"

namespace spline {
namespace {

using testing::small_surface;

// The patch of `face` containing face point b (largest smallest coordinate), and its
// coordinates.
struct Located {
  const BezierPatch* patch = nullptr;
  Eigen::Vector3d lambda;
};
Located locate(const std::vector<const BezierPatch*>& patches, const Eigen::Vector3d& b) {
  Located best;
  double worst = -1e300;
  for (const BezierPatch* p : patches) {
    const Eigen::Vector3d l = p->corners.fullPivLu().solve(b);
    if (l.minCoeff() > worst) {
      worst = l.minCoeff();
      best = {p, l};
    }
  }
  return best;
}

// The export of each model, made once per binary.
const BezierExport& exported(const std::string& name) {
  static std::map<std::string, BezierExport> cache;
  auto it = cache.find(name);
  if (it == cache.end()) it = cache.emplace(name, bezier_patches(small_surface(name))).first;
  return it->second;
}

class BezierExportTest : public ::testing::TestWithParam<const char*> {};

TEST_P(BezierExportTest, PatchesAreTheSplinesPieces) {
  const SplineSurface& s = small_surface(GetParam());
  const ManifoldSplineSpace& space = *s.spline.space;
  const BezierExport& e = exported(GetParam());
  const int n = e.degree;
  ASSERT_EQ(n, space.degree());
  std::map<int, std::vector<const BezierPatch*>> by_face;
  for (const BezierPatch& p : e.patches) by_face[p.face].push_back(&p);
  ASSERT_EQ(static_cast<int>(by_face.size()), e.faces);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  for (const BezierPatch& p : e.patches) {
    lo = lo.cwiseMin(p.control_points.colwise().minCoeff().transpose());
    hi = hi.cwiseMax(p.control_points.colwise().maxCoeff().transpose());
  }
  const double diagonal = (hi - lo).norm();
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst = 0.0;
  for (const auto& [face, patches] : by_face) {
    // The patches tile the face: their areas (in barycentric units) sum to the face's.
    double area = 0.0;
    for (const BezierPatch* p : patches) area += std::abs(p->corners.determinant());
    EXPECT_NEAR(area, 1.0, 1e-9) << "face " << face;
    for (int k = 0; k < 4; ++k) {
      Eigen::Vector3d b(u(rng), u(rng), u(rng));
      b /= b.sum();
      const Located at = locate(patches, b);
      ASSERT_GT(at.lambda.minCoeff(), -1e-9);
      const Eigen::Vector3d bezier = evaluate_bezier(at.patch->control_points, n, at.lambda);
      const double error = (bezier - s.spline.evaluate({face, b}).position).norm();
      worst = std::max(worst, error);
      EXPECT_LT(error, 1e-12 * diagonal) << "face " << face;
    }
  }
  RecordProperty("worst_relative_error", std::to_string(worst / diagonal));
  RecordProperty("patches", static_cast<int>(e.patches.size()));
}

TEST_P(BezierExportTest, NeighbouringPatchesMeetWithCnMinus1) {
  const SplineSurface& s = small_surface(GetParam());
  const ManifoldSplineSpace& space = *s.spline.space;
  const BezierExport& e = exported(GetParam());
  const int n = e.degree;
  std::map<int, std::vector<const BezierPatch*>> by_face;
  for (const BezierPatch& p : e.patches) by_face[p.face].push_back(&p);
  double diagonal = 0.0;
  {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
    for (const BezierPatch& p : e.patches) {
      lo = lo.cwiseMin(p.control_points.colwise().minCoeff().transpose());
      hi = hi.cwiseMax(p.control_points.colwise().maxCoeff().transpose());
    }
    diagonal = (hi - lo).norm();
  }
  const std::vector<int> rings = domain_rim_rings(space);
  constexpr int kRings = 3;
  int edges = 0, jumps = 0;
  double size = 0.0;  // a length of the surface: the largest |F_u| h over the faces
  for (const auto& [f, patches_f] : by_face) {
    const auto c = space.atlas().face_positions(space.chart_of(f), f);
    const SurfaceJet j = s.spline.evaluate({f, Eigen::Vector3d::Constant(1.0 / 3.0)});
    size = std::max(size, j.du.norm() * (c.row(1) - c.row(0)).norm());
  }
  for (const auto& [f, patches_f] : by_face) {
    const int chart = space.chart_of(f);
    const auto cf = space.atlas().face_positions(chart, f);
    for (int k = 0; k < 3; ++k) {
      const int g = space.neighbour(f, k);
      if (g < f || by_face.count(g) == 0) continue;
      // Away from the singularity: beyond the first rings around the cone's hole, where the
      // chart's scale changes by large factors from face to face.
      if (rings[space.domain_index(f)] >= 0 && (rings[space.domain_index(f)] < kRings ||
                                                rings[space.domain_index(g)] < kRings)) {
        continue;
      }
      const auto cg = space.atlas().face_positions(chart, g);
      const Eigen::Vector2d a = cf.row((k + 1) % 3).transpose();
      const Eigen::Vector2d b = cf.row((k + 2) % 3).transpose();
      // Across the edge and along it, unit length in the chart.
      const Eigen::Vector2d along = (b - a).normalized();
      const Eigen::Vector2d across(-along.y(), along.x());
      const auto bary = [](const Eigen::Matrix<double, 3, 2>& c, const Eigen::Vector2d& x) {
        Eigen::Matrix3d m;
        m << c.transpose(), Eigen::RowVector3d::Ones();
        return Eigen::Vector3d(m.fullPivLu().solve(Eigen::Vector3d(x.x(), x.y(), 1.0)));
      };
      const double h = (b - a).norm();
      for (double t : {0.31, 0.5, 0.73}) {
        const Eigen::Vector2d x = a + t * (b - a);
        const Located pf = locate(patches_f, bary(cf, x));
        const Located pg = locate(by_face[g], bary(cg, x));
        for (const Eigen::Vector2d& d : {across, along}) {
          // d in each patch's own barycentric coordinates.
          const Eigen::Vector3d df =
              pf.patch->corners.fullPivLu().solve(bary(cf, x + d) - bary(cf, x));
          const Eigen::Vector3d dg =
              pg.patch->corners.fullPivLu().solve(bary(cg, x + d) - bary(cg, x));
          for (int order = 0; order < n; ++order) {
            const Eigen::Vector3d vf =
                bezier_derivative(pf.patch->control_points, n, pf.lambda, df, order);
            const Eigen::Vector3d vg =
                bezier_derivative(pg.patch->control_points, n, pg.lambda, dg, order);
            // Derivatives of order k scale like (size / h^k): compare in those units. A patch
            // carries its control points' rounding (~1e-16 of the diagonal) into its k-th
            // derivative amplified by |direction in its barycentric coordinates|^k, which is
            // large across the thin cells next to knot segments (cells 1e-5 of an edge wide).
            const double rounding =
                1e-12 * diagonal * std::pow(n, order) *
                (std::pow(df.lpNorm<1>(), order) + std::pow(dg.lpNorm<1>(), order));
            const double unit = std::max(vf.norm(), size / std::pow(h, order)) + rounding * 1e6;
            // The spline's own one-sided derivatives (up to order 2): where they jump (knots
            // in special position) the patches must jump the same way.
            double spline_jump = 0.0;
            if (order <= 2) {
              const SurfaceJet sf = s.spline.evaluate_at(chart, f, x, TieBreak{across});
              const SurfaceJet sg = s.spline.evaluate_at(chart, g, x, TieBreak{-across});
              const auto directional = [&](const SurfaceJet& j) -> Eigen::Vector3d {
                if (order == 0) return j.position;
                if (order == 1) return d.x() * j.du + d.y() * j.dv;
                return d.x() * d.x() * j.duu + 2 * d.x() * d.y() * j.duv + d.y() * d.y() * j.dvv;
              };
              spline_jump = (directional(sf) - directional(sg)).norm();
              EXPECT_LT((vf - directional(sf)).norm(), 1e-6 * unit) << "face " << f;
              EXPECT_LT((vg - directional(sg)).norm(), 1e-6 * unit) << "face " << g;
            }
            if (spline_jump > 1e-6 * unit) ++jumps;
            EXPECT_LT((vf - vg).norm(), spline_jump + 1e-6 * unit)
                << "faces " << f << " " << g << " order " << order;
          }
        }
      }
      ++edges;
    }
  }
  EXPECT_GT(edges, 100);
  // C^(n-1) across almost every edge: the spline's own jumps (knots in special position) are rare.
  EXPECT_LT(jumps, edges / 50) << jumps << " jumps over " << edges << " edges";
  RecordProperty("jumps", jumps);
}

INSTANTIATE_TEST_SUITE_P(Bundled, BezierExportTest,
                         ::testing::Values("genus0.off", "genus1.off", "genus2.off",
                                           "genus3.off"));

TEST(BezierExport, PolynomialCellsOfABadFaceThrow) {
  const SplineSurface& s = small_surface("genus1.off");
  EXPECT_THROW((void)polynomial_cells(*s.spline.space, -1), ricci::InvalidInputError);
}

TEST(BezierExport, BlossomOfADegreeTwoTriangle) {
  // p(lambda) = sum_beta c_beta B_beta(lambda); with c_beta = beta the patch is n * lambda.
  const int n = 2;
  Eigen::MatrixX3d c(multi_index_count(n), 3);
  const auto betas = multi_indices(n);
  for (std::size_t i = 0; i < betas.size(); ++i) {
    c.row(static_cast<Eigen::Index>(i)) = betas[i].cast<double>().transpose();
  }
  const Eigen::Vector3d lambda(0.2, 0.3, 0.5);
  EXPECT_NEAR((evaluate_bezier(c, n, lambda) - n * lambda).norm(), 0.0, 1e-15);
  const Eigen::Vector3d d(1.0, -1.0, 0.0);
  EXPECT_NEAR((bezier_derivative(c, n, lambda, d, 1) - n * d).norm(), 0.0, 1e-14);
  EXPECT_NEAR(bezier_derivative(c, n, lambda, d, 2).norm(), 0.0, 1e-14);
  EXPECT_THROW((void)bezier_blossom(c, n, {lambda}), ricci::InvalidInputError);
}

}  // namespace
}  // namespace spline

// The geometry behind `msp atlas -o picture.svg`: outline, cut sides, copies of the domain.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "apps/atlas_test_util.h"
#include "msp/svg_atlas.h"
#include "msp/svg_cover.h"

namespace {

using msp_test::genus2_atlas;
using msp_test::torus_atlas;

// Sum over the domain and its copies of their winding numbers around p: how many layers of the
// patch cover p.
int layers(const Eigen::MatrixX2d& outline, const std::vector<ricci::RigidMotion2>& copies,
           const Eigen::Vector2d& p) {
  int total = msp::winding_number(outline, p);
  for (const auto& m : copies) total += msp::winding_number(msp::transformed(outline, m), p);
  return total;
}

double min_boundary_edge(const Eigen::MatrixX2d& outline) {
  double shortest = INFINITY;
  for (Eigen::Index i = 0; i < outline.rows(); ++i) {
    shortest = std::min(shortest, (outline.row((i + 1) % outline.rows()) - outline.row(i)).norm());
  }
  return shortest;
}

// Interior angle of the counter-clockwise polygon at vertex i, in (0, 2 pi).
double interior_angle(const Eigen::MatrixX2d& p, Eigen::Index i) {
  const Eigen::Index n = p.rows();
  const Eigen::Vector2d to_prev = p.row((i + n - 1) % n) - p.row(i),
                        to_next = p.row((i + 1) % n) - p.row(i);
  double a =
      std::atan2(to_next.x() * to_prev.y() - to_next.y() * to_prev.x(), to_next.dot(to_prev));
  if (a <= 0) a += 2 * M_PI;
  return a;
}

TEST(AtlasPicture, OutlineIsCounterClockwiseWithTheChartsArea) {
  for (const auto* r : {&torus_atlas(), &genus2_atlas()}) {
    const msp::DomainOutline outline = msp::domain_outline(r->atlas);
    double chart_area = 0.0;
    const auto& x = r->atlas.layout.positions;
    for (auto f : r->atlas.sliced.mesh.faces()) {
      Eigen::Vector2d p[3];
      int k = 0;
      for (auto v : r->atlas.sliced.mesh.fv_range(f)) p[k++] = x.row(v.idx()).transpose();
      const Eigen::Vector2d e1 = p[1] - p[0], e2 = p[2] - p[0];
      chart_area += 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
    }
    // The outline bounds the laid-out disk: same area (the disk is immersed, so by winding).
    EXPECT_NEAR(outline.signed_area, chart_area, 1e-10 * chart_area);
    EXPECT_EQ(outline.vertices.size(), static_cast<size_t>(outline.points.rows()));
  }
}

TEST(AtlasPicture, ConeCornersAddUpToTheConeAngle) {
  // Gauss-Bonnet on the polygon: its corners at copies of the cone add up to the cone angle
  // 2 pi - K = 6 pi (genus 2), as the flow left it.
  const auto& r = genus2_atlas();
  const msp::DomainOutline outline = msp::domain_outline(r.atlas);
  const int root = r.atlas.cut.root.idx();
  ASSERT_EQ(root, r.problem.cone);
  double corners = 0.0;
  int copies = 0;
  for (size_t i = 0; i < outline.vertices.size(); ++i) {
    if (r.atlas.sliced.to_original_vertex[static_cast<size_t>(outline.vertices[i])] != root)
      continue;
    corners += interior_angle(outline.points, static_cast<Eigen::Index>(i));
    ++copies;
  }
  EXPECT_EQ(copies, 8);  // 4g corners of the canonical polygon
  EXPECT_NEAR(corners, 2 * M_PI - r.flow.curvature[root], 1e-9);
  EXPECT_NEAR(corners, 6 * M_PI, 1e-9);
}

TEST(AtlasPicture, SidePairingsMapLeftSidesOntoRightSides) {
  for (const auto* r : {&torus_atlas(), &genus2_atlas()}) {
    const auto sides = msp::cut_sides(r->problem.mesh, r->atlas);
    ASSERT_EQ(sides.size(), 2 * r->atlas.side_pairings.size());
    for (size_t s = 0; s < sides.size(); s += 2) {
      ASSERT_TRUE(sides[s].left);
      ASSERT_FALSE(sides[s + 1].left);
      const auto& motion = r->atlas.side_pairings[static_cast<size_t>(sides[s].pairing)].motion;
      const Eigen::MatrixX2d moved = msp::transformed(sides[s].points, motion);
      EXPECT_LT((moved - sides[s + 1].points).rowwise().norm().maxCoeff(),
                1e-9 * r->atlas.domain_diameter);
    }
  }
}

TEST(AtlasPicture, TorusCopiesTileThePlaneWithoutGapsOrOverlaps) {
  const auto& r = torus_atlas();
  const msp::DomainOutline outline = msp::domain_outline(r.atlas);
  const auto copies = msp::cover_motions(r.atlas, msp::resolved_cover_depth(r, -1));
  ASSERT_EQ(msp::resolved_cover_depth(r, -1), 2);
  for (const auto& m : copies)
    EXPECT_LT(std::abs(m.angle), 1e-9) << "a torus's deck transformations are translations";
  if (r.atlas.side_pairings.size() == 2) {
    EXPECT_EQ(copies.size(), 12u);  // {i a + j b : 0 < |i| + |j| <= 2}
  }

  // The loops' translations span the lattice whose cell has the domain's area.
  std::vector<Eigen::Vector2d> loop_translations;
  for (const auto& side : r.atlas.side_pairings) {
    if (side.loop >= 0) loop_translations.push_back(side.motion.translation);
  }
  ASSERT_EQ(loop_translations.size(), 2u);
  const double cell = std::abs(loop_translations[0].x() * loop_translations[1].y() -
                               loop_translations[0].y() * loop_translations[1].x());
  EXPECT_NEAR(cell, outline.signed_area, 1e-9 * outline.signed_area);

  // Points just around every corner and edge of the domain, and inside it, are covered exactly
  // once by the patch.
  const double eps = 0.05 * min_boundary_edge(outline.points);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> turn(0, 2 * M_PI);
  int checked = 0;
  for (Eigen::Index i = 0; i < outline.points.rows(); ++i) {
    for (int k = 0; k < 6; ++k) {
      const double a = turn(random);
      const Eigen::Vector2d p =
          outline.points.row(i).transpose() + eps * Eigen::Vector2d(std::cos(a), std::sin(a));
      ASSERT_EQ(layers(outline.points, copies, p), 1) << "near outline vertex " << i;
      ++checked;
    }
  }
  for (auto f : r.atlas.sliced.mesh.faces()) {
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (auto v : r.atlas.sliced.mesh.fv_range(f))
      c += r.atlas.layout.positions.row(v.idx()).transpose() / 3.0;
    ASSERT_EQ(layers(outline.points, copies, c), 1) << "face " << f.idx();
  }
  EXPECT_GT(checked, 100);
}

TEST(AtlasPicture, Genus2FirstRingHasOneCopyAcrossEachSide) {
  const auto& r = genus2_atlas();
  const msp::DomainOutline outline = msp::domain_outline(r.atlas);
  const auto copies = msp::cover_motions(r.atlas, msp::resolved_cover_depth(r, -1));
  EXPECT_EQ(copies.size(), 2 * r.atlas.side_pairings.size());
  const auto sides = msp::cut_sides(r.problem.mesh, r.atlas);
  for (const auto& side : sides) {
    // Just outside the middle of the side: outside the domain, inside the copy glued there
    // (moved by the pairing for a right side, by its inverse for a left side).
    const auto& pairing = r.atlas.side_pairings[static_cast<size_t>(side.pairing)];
    const Eigen::Index mid = side.points.rows() / 2;
    const Eigen::Vector2d a = side.points.row(mid - 1).transpose(),
                          b = side.points.row(mid).transpose();
    const Eigen::Vector2d tangent = (b - a).normalized();
    const Eigen::Vector2d outward =
        (side.left ? -1.0 : 1.0) * Eigen::Vector2d(-tangent.y(), tangent.x());
    const Eigen::Vector2d p = 0.5 * (a + b) + 0.05 * (b - a).norm() * outward;
    const auto across = side.left ? pairing.motion.inverse() : pairing.motion;
    EXPECT_EQ(msp::winding_number(outline.points, p), 0);
    EXPECT_EQ(msp::winding_number(msp::transformed(outline.points, across), p), 1);
  }
}

TEST(AtlasPicture, SvgDrawsTheCopiesSidesAndCaption) {
  const auto& r = genus2_atlas();
  msp::AtlasSvgOptions options;
  options.title = "eight.off";
  const std::string svg = msp::atlas_svg(r, options);
  auto count = [&](const std::string& what) {
    size_t n = 0;
    for (size_t at = svg.find(what); at != std::string::npos; at = svg.find(what, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_EQ(count("<svg"), 2u);
  EXPECT_EQ(count("</svg>"), 2u);
  EXPECT_EQ(count("class=\"copy\""), 2 * r.atlas.side_pairings.size());
  ASSERT_TRUE(r.atlas.polygon.canonical);
  for (const char* name : {">a1<", ">b1<", ">a2<", ">b2<"}) EXPECT_EQ(count(name), 2u) << name;
  EXPECT_EQ(count("<circle"), 8u);  // the cone's copies at the corners
  EXPECT_NE(svg.find("first ring only"), std::string::npos);
  EXPECT_NE(svg.find("6.00π"), std::string::npos);
  EXPECT_NE(svg.find("eight.off"), std::string::npos);

  const std::string torus = msp::atlas_svg(torus_atlas());
  EXPECT_NE(torus.find("translations tiling the plane"), std::string::npos);
  EXPECT_EQ(torus.find("<circle"), std::string::npos);
}

TEST(AtlasPicture, WindingNumberCountsLayers) {
  Eigen::MatrixX2d square(4, 2);
  square << 0, 0, 1, 0, 1, 1, 0, 1;
  EXPECT_EQ(msp::winding_number(square, {0.5, 0.5}), 1);
  EXPECT_EQ(msp::winding_number(square, {1.5, 0.5}), 0);
  EXPECT_EQ(msp::winding_number(square.colwise().reverse(), {0.5, 0.5}), -1);
  // Twice around the same square.
  Eigen::MatrixX2d twice(8, 2);
  twice << square, square;
  EXPECT_EQ(msp::winding_number(twice, {0.25, 0.75}), 2);
}

}  // namespace

// measure_against_scan and the AABB soups under it: distances both ways, coverage and the
// boundary distance on surfaces whose answers are known in closed form.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/soup_distance.h"
#include "spline/tessellate/dihedral.h"
#include "spline/tessellate/scan_distance.h"

namespace spline {
namespace {

// Two reports of the same surface against the same scan agree bit for bit.
void expect_same_report(const ScanDistanceReport& a, const ScanDistanceReport& b) {
  EXPECT_EQ(a.bbox_diagonal, b.bbox_diagonal);
  EXPECT_EQ(a.coverage, b.coverage);
  EXPECT_EQ(a.fit_rms, b.fit_rms);
  EXPECT_EQ(a.fit_max, b.fit_max);
  EXPECT_EQ(a.fit_max_point, b.fit_max_point);
  EXPECT_EQ(a.surface_to_scan_p99, b.surface_to_scan_p99);
  EXPECT_EQ(a.surface_to_scan_max, b.surface_to_scan_max);
  EXPECT_EQ(a.surface_to_scan_max_point, b.surface_to_scan_max_point);
  EXPECT_EQ(a.scan_boundary_edges, b.scan_boundary_edges);
  EXPECT_EQ(a.boundary_hausdorff, b.boundary_hausdorff);
}

using Triangles = std::vector<std::array<int, 3>>;

struct Grid {
  Eigen::MatrixX3d positions;
  Triangles triangles;
};

// The square [0, width] x [0, 1] at height z, n x n cells of two triangles each.
Grid grid(int n, double width, double z) {
  Grid g;
  g.positions.resize((n + 1) * (n + 1), 3);
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) g.positions.row(j * (n + 1) + i) << width * i / n, 1.0 * j / n, z;
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      g.triangles.push_back({a, b, c});
      g.triangles.push_back({a, c, d});
    }
  }
  return g;
}

TEST(TriangleSoupDistance, ClosestPointsOfASquareAreKnown) {
  const Grid g = grid(4, 1.0, 0.0);
  const ricci::TriangleSoupDistance soup(g.positions, g.triangles);
  EXPECT_EQ(soup.triangle_count(), 32);
  const ricci::SoupHit above = soup.closest(Eigen::Vector3d(0.3, 0.6, 0.25));
  EXPECT_NEAR(above.distance, 0.25, 1e-15);
  EXPECT_TRUE(above.point.isApprox(Eigen::Vector3d(0.3, 0.6, 0.0), 1e-15));
  // Outside the square: the distance to its nearest edge point (1, 1, 0).
  EXPECT_NEAR(soup.closest(Eigen::Vector3d(2.0, 2.0, 0.0)).distance, std::sqrt(2.0), 1e-14);
  Eigen::MatrixX3d queries(2, 3);
  queries << 0.5, 0.5, -1.0, 0.1, 0.9, 0.5;
  const Eigen::VectorXd d = soup.distances(queries);
  EXPECT_NEAR(d[0], 1.0, 1e-15);
  EXPECT_NEAR(d[1], 0.5, 1e-15);
}

TEST(TriangleSoupDistance, DegenerateTrianglesAreLeftOutAndBadSoupsThrow) {
  Eigen::MatrixX3d p(4, 3);
  p << 0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0;
  const ricci::TriangleSoupDistance soup(p, {{0, 1, 2}, {0, 0, 3}, {0, 1, 3}});
  EXPECT_EQ(soup.triangle_count(), 1);
  EXPECT_EQ(soup.closest(Eigen::Vector3d(0.2, 0.2, 1.0)).primitive, 2);
  EXPECT_THROW(ricci::TriangleSoupDistance(p, {{0, 1, 2}}), ricci::InvalidInputError);
  EXPECT_THROW(ricci::TriangleSoupDistance(p, {{0, 1, 7}}), ricci::InvalidInputError);
  p(3, 1) = std::nan("");
  EXPECT_THROW(ricci::TriangleSoupDistance(p, {{0, 1, 3}}), ricci::InvalidInputError);
}

// A wavy sheet z = 0.1 sin(5x) cos(4y) over the unit square, n x n cells, lifted by `z`.
Grid wavy(int n, double z) {
  Grid g = grid(n, 1.0, z);
  for (Eigen::Index v = 0; v < g.positions.rows(); ++v)
    g.positions(v, 2) +=
        0.1 * std::sin(5.0 * g.positions(v, 0)) * std::cos(4.0 * g.positions(v, 1));
  return g;
}

TEST(TriangleSoupDistance, AHintGivesTheSameNearestDistance) {
  const Grid g = wavy(12, 0.0);
  const ricci::TriangleSoupDistance soup(g.positions, g.triangles);
  // Hints near and far from each query: the search bound changes, the answer does not.
  const ricci::SoupHit far = soup.closest(Eigen::Vector3d(1.0, 1.0, 0.0));
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d q(-0.2 + 1.4 * std::fmod(0.37 * i, 1.0),
                            -0.2 + 1.4 * std::fmod(0.61 * i, 1.0), 0.3 * std::sin(i));
    const ricci::SoupHit plain = soup.closest(q);
    const ricci::SoupHit nearby = soup.closest(q + Eigen::Vector3d(0.01, -0.02, 0.0));
    EXPECT_NEAR(soup.closest(q, far).distance, plain.distance, 1e-15) << i;
    EXPECT_NEAR(soup.closest(q, nearby).distance, plain.distance, 1e-15) << i;
  }
  ricci::SoupHit bad = far;
  bad.primitive = static_cast<int>(g.triangles.size());
  EXPECT_THROW((void)soup.closest(Eigen::Vector3d::Zero(), bad), ricci::InvalidInputError);
  Eigen::MatrixX3d p(4, 3);
  p << 0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0;
  const ricci::TriangleSoupDistance flat(p, {{0, 1, 2}, {0, 1, 3}});
  ricci::SoupHit degenerate;
  degenerate.primitive = 0;  // collinear: not in the tree
  EXPECT_THROW((void)flat.closest(Eigen::Vector3d::Zero(), degenerate), ricci::InvalidInputError);
}

TEST(SegmentSoupDistance, DistanceToAPolyline) {
  Eigen::MatrixX3d p(3, 3);
  p << 0, 0, 0, 1, 0, 0, 1, 1, 0;
  const ricci::SegmentSoupDistance curve(p, {{0, 1}, {1, 2}});
  EXPECT_NEAR(curve.closest(Eigen::Vector3d(0.5, -0.5, 0.0)).distance, 0.5, 1e-15);
  EXPECT_NEAR(curve.closest(Eigen::Vector3d(2.0, 0.5, 0.0)).distance, 1.0, 1e-15);
  EXPECT_EQ(curve.closest(Eigen::Vector3d(2.0, 0.5, 0.0)).primitive, 1);
  EXPECT_THROW(ricci::SegmentSoupDistance(p, {}), ricci::InvalidInputError);
}

TEST(MeasureAgainstScan, AParallelCopyIsItsOffsetAwayBothWays) {
  const Grid scan = grid(10, 1.0, 0.0);
  const Grid surface = grid(7, 1.0, 0.01);  // another triangulation, lifted by 0.01
  ScanDistanceOptions options;
  options.coverage_tolerance = 0.02;  // of the diagonal sqrt(2): 0.028 > 0.01
  const ScanDistanceReport r = measure_against_scan(surface.positions, surface.triangles,
                                                    scan.positions, scan.triangles, options);
  EXPECT_NEAR(r.bbox_diagonal, std::sqrt(2.0), 1e-15);
  EXPECT_EQ(r.scan_points, 121);
  EXPECT_EQ(r.surface_points, 64 + 98);
  EXPECT_NEAR(r.fit_rms, 0.01, 1e-12);
  EXPECT_NEAR(r.fit_max, 0.01, 1e-12);
  EXPECT_NEAR(r.surface_to_scan_p99, 0.01, 1e-12);
  EXPECT_NEAR(r.surface_to_scan_max, 0.01, 1e-12);
  EXPECT_NEAR(r.coverage, 1.0, 1e-15);
  EXPECT_NEAR(r.boundary_hausdorff, 0.01, 1e-12);
  options.coverage_tolerance = 0.005;  // 0.0071 < 0.01: nothing covered
  EXPECT_NEAR(measure_against_scan(surface.positions, surface.triangles, scan.positions,
                                   scan.triangles, options)
                  .coverage,
              0.0, 1e-15);
}

TEST(MeasureAgainstScan, OneThreadOrTwoGiveTheSameReport) {
  const Grid scan = wavy(40, 0.0);
  // Another triangulation, lifted: its steep flanks lie within the tolerance, its flat parts not.
  const Grid surface = wavy(23, 0.003);
  ScanDistanceOptions options;
  options.coverage_tolerance = 0.002;  // 0.0028 absolute, below the offset on the flat parts
  options.threads = 1;
  const ScanDistanceReport one = measure_against_scan(surface.positions, surface.triangles,
                                                      scan.positions, scan.triangles, options);
  options.threads = 2;
  const ScanDistanceReport two = measure_against_scan(surface.positions, surface.triangles,
                                                      scan.positions, scan.triangles, options);
  EXPECT_GT(one.coverage, 0.02);
  EXPECT_LT(one.coverage, 0.98);
  expect_same_report(one, two);
  // Coverage by brute force: each scan triangle's four samples against every surface triangle.
  const ricci::TriangleSoupDistance tree(surface.positions, surface.triangles);
  double covered = 0.0, total = 0.0;
  for (const auto& t : scan.triangles) {
    const Eigen::Vector3d a = scan.positions.row(t[0]), b = scan.positions.row(t[1]),
                          c = scan.positions.row(t[2]);
    const double area = 0.5 * (b - a).cross(c - a).norm();
    const Eigen::Vector3d samples[4] = {(a + b + c) / 3.0, (4.0 * a + b + c) / 6.0,
                                        (a + 4.0 * b + c) / 6.0, (a + b + 4.0 * c) / 6.0};
    for (const auto& s : samples)
      covered += area / 4.0 * (tree.closest(s).distance <= one.coverage_tolerance);
    total += area;
  }
  EXPECT_NEAR(one.coverage, covered / total, 1e-14);
}

TEST(MeasureAgainstScan, APreparedScanGivesTheSameReportForEverySurface) {
  const Grid scan = wavy(40, 0.0);
  const PreparedScan prepared(scan.positions, scan.triangles);
  ScanDistanceOptions options;
  options.coverage_tolerance = 0.002;
  // Two surfaces against the one prepared scan, each as measured with the scan's own tree.
  for (const Grid& surface : {wavy(23, 0.003), grid(7, 0.6, 0.01)}) {
    const ScanDistanceReport own = measure_against_scan(surface.positions, surface.triangles,
                                                        scan.positions, scan.triangles, options);
    const ScanDistanceReport shared =
        measure_against_scan(surface.positions, surface.triangles, prepared, options);
    EXPECT_GT(own.fit_max, 0.0);
    expect_same_report(own, shared);
  }
  Triangles bad = scan.triangles;
  bad[0][1] = static_cast<int>(scan.positions.rows());
  EXPECT_THROW(PreparedScan(scan.positions, bad), ricci::InvalidInputError);
}

// Samples measured ahead on a surface that shares most of its points with the one measured
// later (a patch added, a region moved) give that surface's report bit for bit, whether its
// farthest point is among the known samples or the new ones.
TEST(MeasureAgainstScan, SamplesMeasuredAheadGiveTheSameReport) {
  const Grid scan = wavy(40, 0.0);
  const PreparedScan prepared(scan.positions, scan.triangles);
  const Grid before = wavy(23, 0.003);
  const KnownSampleDistances known(before.positions, before.triangles, prepared, 2);
  EXPECT_EQ(known.vertex_count(), static_cast<std::size_t>(before.positions.rows()));
  EXPECT_EQ(known.centroid_count(), before.triangles.size());
  ScanDistanceOptions options;
  options.coverage_tolerance = 0.002;
  for (const double lift : {0.001, 0.05}) {
    Grid after = before;
    for (Eigen::Index v = 0; v < after.positions.rows(); ++v)
      if (after.positions(v, 0) < 0.2 && after.positions(v, 1) < 0.3) after.positions(v, 2) += lift;
    // A patch over the corner: new vertices and triangles, some triangles left out.
    const int base = static_cast<int>(after.positions.rows());
    after.positions.conservativeResize(base + 3, 3);
    after.positions.row(base) << 1.1, 1.1, 0.02;
    after.positions.row(base + 1) << 1.2, 1.0, 0.0;
    after.positions.row(base + 2) << 1.0, 1.2, 0.01;
    after.triangles.push_back({base, base + 1, base + 2});
    after.triangles.erase(after.triangles.begin() + 5);
    const ScanDistanceReport fresh =
        measure_against_scan(after.positions, after.triangles, prepared, options);
    options.known_samples = &known;
    const ScanDistanceReport taken =
        measure_against_scan(after.positions, after.triangles, prepared, options);
    options.known_samples = nullptr;
    expect_same_report(fresh, taken);
    EXPECT_EQ(fresh.surface_points, taken.surface_points);
    EXPECT_GT(fresh.surface_to_scan_max, lift);
  }
  // Stopped after one chunk of samples (a finer surface: more than one chunk): fewer samples
  // known, the same report.
  const Grid fine = wavy(60, 0.003);
  int chunks = 0;
  const KnownSampleDistances part(fine.positions, fine.triangles, prepared, 1,
                                  [&chunks] { return ++chunks > 1; });
  EXPECT_GT(part.vertex_count(), 0u);
  EXPECT_LT(part.vertex_count(), static_cast<std::size_t>(fine.positions.rows()));
  EXPECT_LT(part.centroid_count(), fine.triangles.size());
  const ScanDistanceReport plain =
      measure_against_scan(fine.positions, fine.triangles, prepared, options);
  options.known_samples = &part;
  expect_same_report(plain,
                     measure_against_scan(fine.positions, fine.triangles, prepared, options));
  options.known_samples = nullptr;
  // The same answers need the same scan's tree.
  const PreparedScan other(scan.positions, scan.triangles);
  options.known_samples = &known;
  EXPECT_THROW((void)measure_against_scan(before.positions, before.triangles, other, options),
               ricci::InvalidInputError);
  EXPECT_THROW((void)measure_against_scan(before.positions, before.triangles, scan.positions,
                                          scan.triangles, options),
               ricci::InvalidInputError);
}

TEST(MeasureAgainstScan, ASurfaceThatStopsShortIsSeenFromTheScan) {
  const Grid scan = grid(10, 1.0, 0.0);
  const Grid half = grid(5, 0.5, 0.0);  // covers x <= 0.5 only
  const ScanDistanceReport r =
      measure_against_scan(half.positions, half.triangles, scan.positions, scan.triangles);
  EXPECT_NEAR(r.fit_max, 0.5, 1e-12);              // the scan's far side
  EXPECT_NEAR(r.surface_to_scan_max, 0.0, 1e-12);  // the surface lies on the scan
  EXPECT_NEAR(r.coverage, 0.5, 1e-12);             // the right half's samples are >= 0.1 / 6 away
  EXPECT_NEAR(r.scan_boundary_to_surface_boundary, 0.5, 1e-12);
  // The cut x = 0.5 is half a unit from the scan's rim at its middle.
  EXPECT_NEAR(r.surface_boundary_to_scan_boundary, 0.5, 1e-12);
  EXPECT_NEAR(r.boundary_hausdorff, 0.5, 1e-12);
}

TEST(MeasureAgainstScan, ASpikeIsSeenFromTheSurfaceOnly) {
  const Grid scan = grid(10, 1.0, 0.0);
  Grid spiked = scan;
  spiked.positions(60, 2) = 3.0;  // the vertex (0.5, 0.5) pulled 3 units up
  const ScanDistanceReport r =
      measure_against_scan(spiked.positions, spiked.triangles, scan.positions, scan.triangles);
  EXPECT_NEAR(r.surface_to_scan_max, 3.0, 1e-12);
  EXPECT_TRUE(r.surface_to_scan_max_point.isApprox(Eigen::Vector3d(0.5, 0.5, 3.0), 1e-12));
  // Every scan vertex is still near the spiked surface (the centre 0.1 / sqrt(1 + 1/900) from
  // the spike's flanks).
  EXPECT_LT(r.fit_max, 0.1);
  const DihedralReport folds = dihedral_angles(spiked.triangles, spiked.positions);
  EXPECT_EQ(folds.over_90_deg, static_cast<int>(folds.fold_edges.size()));
}

// Triangles left out of the surface-to-scan direction (a patch over a hole of the scan): the
// spike on them is not seen there, its samples are counted as left out, the other way is whole.
TEST(MeasureAgainstScan, UnmeasuredTrianglesAreLeftOutAndCounted) {
  const Grid scan = grid(10, 1.0, 0.0);
  Grid spiked = scan;
  spiked.positions(60, 2) = 3.0;
  ScanDistanceOptions options;
  options.unmeasured_surface_triangles.assign(spiked.triangles.size(), 0);
  int spike_triangles = 0;
  for (std::size_t t = 0; t < spiked.triangles.size(); ++t) {
    for (int v : spiked.triangles[t]) {
      if (v == 60) {
        options.unmeasured_surface_triangles[t] = 1;
        ++spike_triangles;
        break;
      }
    }
  }
  ASSERT_EQ(spike_triangles, 6);
  const ScanDistanceReport r = measure_against_scan(spiked.positions, spiked.triangles,
                                                    scan.positions, scan.triangles, options);
  EXPECT_NEAR(r.surface_to_scan_max, 0.0, 1e-12);
  EXPECT_EQ(r.surface_points_left_out, 6 + 1);  // their centroids and the spike's vertex
  EXPECT_EQ(r.surface_points + r.surface_points_left_out, 121 + 200);
  EXPECT_EQ(r.scan_points, 121);
  options.unmeasured_surface_triangles.pop_back();
  EXPECT_THROW((void)measure_against_scan(spiked.positions, spiked.triangles, scan.positions,
                                          scan.triangles, options),
               ricci::InvalidInputError);
}

// A scan with one triangle missing in the middle, measured against a surface that covers it:
// the hole's rim is half a unit from the surface's boundary unless its vertices are flagged.
TEST(MeasureAgainstScan, FlaggedScanBoundaryIsLeftOutOfTheBoundaryComparison) {
  const Grid surface = grid(10, 1.0, 0.0);
  Grid scan = surface;
  ASSERT_EQ(scan.triangles[110], (std::array<int, 3>{60, 61, 72}));  // cell (5, 5)
  scan.triangles.erase(scan.triangles.begin() + 110);
  const ScanDistanceReport open =
      measure_against_scan(surface.positions, surface.triangles, scan.positions, scan.triangles);
  EXPECT_EQ(open.scan_boundary_edges, 40 + 3);
  EXPECT_NEAR(open.boundary_hausdorff, 0.5, 1e-12);  // vertex 60 = (0.5, 0.5)
  ScanDistanceOptions options;
  options.unmeasured_scan_boundary.assign(static_cast<std::size_t>(scan.positions.rows()), 0);
  for (int v : {60, 61, 72}) options.unmeasured_scan_boundary[static_cast<std::size_t>(v)] = 1;
  const ScanDistanceReport r = measure_against_scan(surface.positions, surface.triangles,
                                                    scan.positions, scan.triangles, options);
  EXPECT_EQ(r.scan_boundary_edges, 40);
  EXPECT_EQ(r.scan_boundary_edges_left_out, 3);
  EXPECT_NEAR(r.boundary_hausdorff, 0.0, 1e-12);
  EXPECT_EQ(r.fit_max, 0.0);  // the vertices still measured
  options.unmeasured_scan_boundary.pop_back();
  EXPECT_THROW((void)measure_against_scan(surface.positions, surface.triangles, scan.positions,
                                          scan.triangles, options),
               ricci::InvalidInputError);
}

TEST(MeasureAgainstScan, ClosedSurfacesHaveNoBoundaryFigure) {
  Eigen::MatrixX3d p(4, 3);
  p << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  const Triangles tetra = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  const ScanDistanceReport r = measure_against_scan(p, tetra, p, tetra);
  EXPECT_EQ(r.scan_boundary_edges, 0);
  EXPECT_EQ(r.boundary_hausdorff, -1.0);
  EXPECT_EQ(r.fit_max, 0.0);
  EXPECT_THROW((void)measure_against_scan(p, {}, p, tetra), ricci::InvalidInputError);
}

}  // namespace
}  // namespace spline

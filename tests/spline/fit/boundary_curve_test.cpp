// boundary_curve_points: the domain's boundary edges sampled, each sample aimed at the nearest
// point of the scan's boundary curve, and the scan's boundary vertices put on the domain's
// boundary; both as repeated data points of the fit.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/primitives.h"
#include "ricci/topology/slice.h"
#include "spline/fit/boundary_curve.h"

namespace spline {
namespace {

// The 3D point of a domain point on `mesh` (corner k of face f is to_vertex(h_k)).
Eigen::Vector3d position(const ricci::Mesh& mesh, const DomainPoint& p) {
  const auto hs = ricci::face_halfedges(mesh, mesh.face_handle(p.face));
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k)
    x += p.barycentric[k] * ricci::to_eigen(mesh.point(mesh.to_vertex_handle(hs[k])));
  return x;
}

// True when p lies on an edge of its face that is a boundary edge of `mesh`.
bool on_boundary_edge(const ricci::Mesh& mesh, const DomainPoint& p) {
  const auto hs = ricci::face_halfedges(mesh, mesh.face_handle(p.face));
  for (int j = 0; j < 3; ++j) {
    // Edge h_j runs from corner j + 2 to corner j; the third corner (j + 1) has weight 0 on it.
    if (std::abs(p.barycentric[(j + 1) % 3]) < 1e-15 &&
        mesh.is_boundary(mesh.opposite_halfedge_handle(hs[j])))
      return true;
  }
  return false;
}

// A coarse disk (16 boundary edges, chords 1.9% inside the unit circle) against a fine one
// (96 boundary vertices on the unit circle).
TEST(BoundaryCurve, SamplesTheDomainsBoundaryOntoTheScansBoundary) {
  const ricci::Mesh coarse = ricci::make_disk(2, 8), fine = ricci::make_disk(12, 8);
  BoundaryCurveOptions options;
  options.samples_per_edge = 4;
  options.weight = 3;
  // The coarse chords' midpoints are 0.7% of the diagonal inside the fine boundary: past the
  // default max_gap, so only the scan's boundary vertices are kept...
  EXPECT_EQ(boundary_curve_points(coarse, {}, fine, options).parameters.size(), 3u * 96u);
  options.max_gap = 1.0;  // ... and with a wider gap the edge samples too.
  const BoundaryCurvePoints b = boundary_curve_points(coarse, {}, fine, options);
  const std::size_t per_copy = 16 * 4 + 96;
  ASSERT_EQ(b.parameters.size(), 3 * per_copy);
  ASSERT_EQ(b.points.rows(), static_cast<Eigen::Index>(3 * per_copy));
  ASSERT_EQ(b.scan_vertices.size(), 96u);
  for (std::size_t i = 0; i < b.parameters.size(); ++i) {
    const DomainPoint& p = b.parameters[i];
    EXPECT_TRUE(on_boundary_edge(coarse, p)) << i;
    EXPECT_NEAR(p.barycentric.sum(), 1.0, 1e-15);
    // Every target is on the fine disk's boundary polygon: within its chords' sagitta of the
    // unit circle, and never inside the coarse chords.
    const double r = b.points.row(static_cast<Eigen::Index>(i)).norm();
    EXPECT_LE(r, 1.0 + 1e-12) << i;
    EXPECT_GT(r, 1.0 - (1.0 - std::cos(M_PI / 96)) - 1e-12) << i;
  }
  // The copies repeat the first one.
  for (std::size_t i = 0; i < per_copy; ++i) {
    EXPECT_EQ(b.points.row(static_cast<Eigen::Index>(i)),
              b.points.row(static_cast<Eigen::Index>(i + 2 * per_copy)));
  }
  // Each scan boundary vertex sits at the nearest point of the coarse boundary: at most the
  // coarse chords' sagitta 1 - cos(pi / 16) away from it.
  for (std::size_t i = 0; i < b.scan_vertices.size(); ++i) {
    const Eigen::Vector3d x = ricci::to_eigen(fine.point(fine.vertex_handle(b.scan_vertices[i])));
    const Eigen::Vector3d u = position(coarse, b.scan_vertex_parameters[i]);
    EXPECT_LE((x - u).norm(), 1.0 - std::cos(M_PI / 16) + 1e-12) << i;
    EXPECT_TRUE(on_boundary_edge(coarse, b.scan_vertex_parameters[i])) << i;
  }
}

// The surface's faces chosen by flags: the boundary is where a surface face meets a non-surface
// face (here the disk's outer ring is left out, as a collar would be).
TEST(BoundaryCurve, SurfaceFlagsSetTheBoundaryAndBadOptionsThrow) {
  const ricci::Mesh coarse = ricci::make_disk(2, 8), fine = ricci::make_disk(12, 8);
  std::vector<char> surface(coarse.n_faces(), 1);
  int inner = 0;
  for (auto f : coarse.faces()) {
    bool touches_rim = false;
    for (auto v : coarse.fv_range(f)) touches_rim |= coarse.is_boundary(v);
    surface[static_cast<std::size_t>(f.idx())] = !touches_rim;
    inner += !touches_rim;
  }
  ASSERT_GT(inner, 0);
  BoundaryCurveOptions options;
  options.weight = 1;
  options.max_gap = 1.0;  // the inner ring is far inside the fine disk's boundary
  const BoundaryCurvePoints b = boundary_curve_points(coarse, surface, fine, options);
  ASSERT_FALSE(b.parameters.empty());
  for (const DomainPoint& p : b.parameters) {
    EXPECT_TRUE(surface[static_cast<std::size_t>(p.face)]);
    EXPECT_LT(position(coarse, p).norm(), 0.9);  // the inner ring's boundary, not the disk's
  }
  options.weight = 0;
  EXPECT_TRUE(boundary_curve_points(coarse, {}, fine, options).parameters.empty());
  EXPECT_TRUE(boundary_curve_points(coarse, {}, ricci::make_icosphere(1)).parameters.empty());
  options.weight = -1;
  EXPECT_THROW((void)boundary_curve_points(coarse, {}, fine, options), ricci::InvalidInputError);
  EXPECT_THROW((void)boundary_curve_points(coarse, std::vector<char>(3, 1), fine),
               ricci::InvalidInputError);
}

}  // namespace
}  // namespace spline

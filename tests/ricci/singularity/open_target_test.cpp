#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "ricci/flow/flow.h"
#include "ricci/mesh/io.h"
#include "ricci/mesh/primitives.h"
#include "ricci/metric/curvature.h"
#include "ricci/metric/mesh_tables.h"
#include "ricci/singularity/one_cone.h"
#include "ricci/singularity/open_target.h"
#include "test_paths.h"

namespace {

ricci::Mesh read_test_mesh(const std::string& relative) {
  return ricci::read_mesh(msp_test::test_mesh(relative));
}

TEST(HarmonicBoundaryTarget, SumsToTwoPiChiWithAFlatInterior) {
  for (const char* path :
       {"open/lion.off.gz", "open/head.off", "open/double-torus-3-holes_quad.off"}) {
    const ricci::Mesh mesh = read_test_mesh(path);
    const ricci::MeshTables t = ricci::build_mesh_tables(mesh);
    const ricci::Targets targets = ricci::harmonic_boundary_target(mesh);
    EXPECT_NEAR(targets.curvature.sum(), 2 * M_PI * t.euler_characteristic, 1e-10) << path;
    for (int v = 0; v < t.num_vertices(); ++v) {
      if (!t.is_boundary_vertex[v]) {
        ASSERT_EQ(targets.curvature[v], 0.0) << path << " vertex " << v;
      }
    }
  }
}

TEST(HarmonicBoundaryTarget, APlanarMeshKeepsItsOwnBoundaryCurvature) {
  // Already flat: du = 0 solves the Dirichlet problem, so the target is the mesh's curvature.
  const ricci::Mesh disk = ricci::make_disk(6, 24);
  const ricci::MeshTables t = ricci::build_mesh_tables(disk);
  const Eigen::VectorXd K =
      ricci::vertex_curvature(t, ricci::mesh_edge_lengths(disk), ricci::Geometry::euclidean);
  const ricci::Targets targets = ricci::harmonic_boundary_target(disk);
  for (int v = 0; v < t.num_vertices(); ++v) {
    EXPECT_NEAR(targets.curvature[v], t.is_boundary_vertex[v] ? K[v] : 0.0, 1e-12) << v;
  }
}

// Spread (max - min) over boundary edges of log(flat length / mesh length): 0 when the boundary
// keeps its shape up to one scale (the flow fixes the global scale by its own normalisation).
double boundary_scale_spread(const ricci::OneConeProblem& problem) {
  const ricci::FlowResult r = ricci::solve_one_cone_flow(problem, ricci::one_cone_flow_options());
  EXPECT_TRUE(r.converged()) << r.message;
  const ricci::MeshTables t = ricci::build_mesh_tables(problem.mesh);
  const Eigen::VectorXd original = ricci::mesh_edge_lengths(problem.mesh);
  double low = 1e300, high = -1e300;
  for (int e = 0; e < t.num_edges(); ++e) {
    if (!t.is_boundary_vertex[t.edge_vertices(e, 0)] || !t.is_boundary_vertex[t.edge_vertices(e, 1)]) continue;
    const double s = std::log(r.lengths[e] / original[e]);
    low = std::min(low, s);
    high = std::max(high, s);
  }
  return high - low;
}

TEST(HarmonicBoundaryTarget, KeepsTheBoundaryShapeBetterThanSpreadingByLength) {
  // The target is the first-order Dirichlet solution (du = 0 on the boundary): after the
  // nonlinear flow the boundary edges keep their lengths up to one scale much better than with
  // 2*pi*chi spread by length (whose flow breaks triangles on this 5-hole scan, so compare on a
  // 3-hole one that both reach).
  const ricci::Mesh mesh = read_test_mesh("open/head.off");
  ricci::OneConeProblem problem = ricci::prepare_one_cone(mesh, -1);
  ASSERT_EQ(problem.kind, ricci::OneConeKind::OpenSurface);
  const double harmonic = boundary_scale_spread(problem);
  problem.targets = ricci::boundary_target(problem.mesh, ricci::BoundaryMode::spread_by_length);
  const double by_length = boundary_scale_spread(problem);
  EXPECT_LT(harmonic, 0.25 * by_length) << harmonic << " vs " << by_length;
}

}  // namespace

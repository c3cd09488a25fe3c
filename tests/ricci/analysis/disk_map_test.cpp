// The conformal map of a disk onto the unit disk (ModuleKind::Disk): the planar unit disk comes
// back as the disk automorphism its normalisation asks for (its boundary, sampled evenly, is
// already round: the metric is the fixed point); a conformal image of it (stereographic, on the
// sphere) gives the same map; bad centres and topologies are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include <ricci/analysis/conformal_module.h>
#include <ricci/mesh/errors.h>

#include "ricci/analysis/analysis_meshes.h"
#include "ricci/test_meshes.h"

namespace ricci {
namespace {

using Complex = std::complex<double>;

ModuleOptions disk_options() {
  ModuleOptions options;
  options.force_kind = true;
  options.kind = ModuleKind::Disk;
  return options;
}

Complex planar(const Mesh& mesh, int v) {
  const auto p = mesh.point(mesh.vertex_handle(v));
  return {p[0], p[1]};
}

/// Largest distance between the map and the disk automorphism that sends the centre to 0 and
/// the vertex at 1 (result.corners) to the positive real axis.
double distance_to_automorphism(const Mesh& planar_mesh, const ModuleResult& r) {
  const Complex c = planar(planar_mesh, r.corners[0]);
  const auto automorphism = [&](Complex z) { return (z - c) / (1.0 - std::conj(c) * z); };
  const Complex one = automorphism(planar(planar_mesh, r.corners[1]));
  const Complex turn = std::conj(one) / std::abs(one);
  double worst = 0;
  for (int v = 0; v < static_cast<int>(planar_mesh.n_vertices()); ++v) {
    const Complex z(r.domain.positions(v, 0), r.domain.positions(v, 1));
    worst = std::max(worst, std::abs(z - turn * automorphism(planar(planar_mesh, v))));
  }
  return worst;
}

TEST(DiskMap, PlanarDiskIsAnAutomorphism) {
  for (double h : {0.1, 0.05}) {
    const Mesh disk = testing::circle_domain_mesh({}, h);
    const ModuleResult r = conformal_module(disk, disk_options());
    ASSERT_TRUE(r.converged) << r.message;
    EXPECT_EQ(r.kind, ModuleKind::Disk);
    EXPECT_TRUE(r.values.empty());
    EXPECT_LT(r.roundness, 1e-6);
    ASSERT_EQ(r.corners.size(), 2u);
    EXPECT_NEAR(r.domain.positions.row(r.corners[0]).norm(), 0.0, 1e-9);
    EXPECT_NEAR(r.domain.positions(r.corners[1], 0), 1.0, 1e-6);
    EXPECT_LT(distance_to_automorphism(disk, r), 1e-6) << h;
  }
}

TEST(DiskMap, ConformalImageGivesTheSameMap) {
  const Mesh disk = testing::circle_domain_mesh({}, 0.05);
  ModuleOptions options = disk_options();
  const ModuleResult flat = conformal_module(disk, options);
  options.centre = flat.corners[0];
  const Mesh cap =
      testing::mapped(disk, [](const Eigen::Vector3d& p) { return testing::onto_sphere(p, 1.5); });
  const ModuleResult lifted = conformal_module(cap, options);
  ASSERT_TRUE(flat.converged && lifted.converged);
  EXPECT_EQ(lifted.corners, flat.corners);
  const double worst =
      (lifted.domain.positions - flat.domain.positions).rowwise().norm().maxCoeff();
  EXPECT_LT(worst, 1e-3) << worst;
}

TEST(DiskMap, BadInput) {
  const Mesh disk = testing::circle_domain_mesh({}, 0.2);
  ModuleOptions options = disk_options();
  options.centre = static_cast<int>(disk.n_vertices());
  EXPECT_THROW((void)conformal_module(disk, options), InvalidInputError);
  options.centre = 0;  // on the rim
  EXPECT_THROW((void)conformal_module(disk, options), InvalidInputError);
  const Mesh annulus = testing::circle_domain_mesh({{0.0, 0.0, 0.3}}, 0.2);
  EXPECT_THROW((void)conformal_module(annulus, disk_options()), InvalidInputError);
  ModuleOptions annulus_centre;
  annulus_centre.centre = 5;
  EXPECT_THROW((void)conformal_module(annulus, annulus_centre), InvalidInputError);
  ModuleKind kind;
  EXPECT_TRUE(parse_module_kind("disk", kind));
  EXPECT_EQ(kind, ModuleKind::Disk);
}

}  // namespace
}  // namespace ricci

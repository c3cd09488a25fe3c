// Conformal modules against closed-form answers: planar annuli ((1/2π) log(R/r)), their
// conformal images in 3D, rectangles (aspect ratio) flat and rolled onto a cylinder, the torus
// of revolution (τ = i sqrt(R²/r² - 1)); invariance under rigid motions and scaling; bad input.
#include <gtest/gtest.h>

#include <cmath>

#include <ricci/analysis/conformal_module.h>
#include <ricci/mesh/errors.h>
#include <ricci/mesh/primitives.h>

#include "ricci/analysis/analysis_meshes.h"
#include "ricci/test_meshes.h"

namespace ricci {
namespace {

constexpr double kInner = 0.4, kOuter = 1.0;
const double kAnnulusModule = std::log(kOuter / kInner) / (2 * M_PI);

/// Log-polar annulus with about `faces` faces and near-square cells.
Mesh annulus_with_faces(int faces) {
  const double ratio = 2 * M_PI / std::log(kOuter / kInner);  // sectors / rings
  const int rings = static_cast<int>(std::lround(std::sqrt(faces / (2 * ratio))));
  const int sectors = static_cast<int>(std::lround(rings * ratio));
  return testing::log_polar_annulus(rings, sectors, kInner, kOuter);
}

double module_of(const Mesh& mesh, const ModuleOptions& options = {}) {
  const ModuleResult result = conformal_module(mesh, options);
  EXPECT_TRUE(result.converged) << result.message;
  EXPECT_EQ(result.values.size(), 1u);
  return result.values.empty() ? NAN : result.values[0];
}

TEST(ConformalModule, PlanarAnnulusConvergesToClosedForm) {
  double previous = INFINITY;
  for (int faces : {1250, 5000, 20000}) {
    Mesh mesh = make_random_perturbed(annulus_with_faces(faces), 0.2, 7);
    const ModuleResult result = conformal_module(mesh);
    ASSERT_TRUE(result.converged) << result.message;
    EXPECT_EQ(result.kind, ModuleKind::Annulus);
    const double error = std::abs(result.values[0] - kAnnulusModule);
    std::cout << faces << " faces: module " << result.values[0] << " error " << error
              << " roundness " << result.roundness << " " << result.seconds << " s\n";
    EXPECT_LT(error, previous);
    previous = error;
  }
  EXPECT_LT(previous, 1e-3);
}

TEST(ConformalModule, AnnulusInThreeDimensions) {
  const Mesh plane = annulus_with_faces(20000);
  const double stereographic = module_of(testing::mapped(
      plane, [](const Eigen::Vector3d& p) { return testing::onto_sphere(p, 0.8); }));
  const double moved = module_of(testing::mapped(plane, [](const Eigen::Vector3d& p) {
    return testing::mobius(p, {0.25, 0.1});
  }));
  std::cout << "stereographic " << stereographic << " mobius " << moved << " exact "
            << kAnnulusModule << "\n";
  EXPECT_NEAR(stereographic, kAnnulusModule, 1e-3);
  EXPECT_NEAR(moved, kAnnulusModule, 1e-3);
}

TEST(ConformalModule, RigidMotionAndScaleChangeNothing) {
  const Mesh mesh = testing::mapped(annulus_with_faces(2000), [](const Eigen::Vector3d& p) {
    return testing::onto_sphere(p, 0.8);
  });
  const double reference = module_of(mesh);
  const Eigen::Matrix3d turn =
      (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())).toRotationMatrix();
  for (double scale : {1.0, 1e-3, 1e3}) {
    const double moved = module_of(testing::mapped(mesh, [&](const Eigen::Vector3d& p) {
      return Eigen::Vector3d(scale * (turn * p) + Eigen::Vector3d(5, -3, 2));
    }));
    EXPECT_NEAR(moved, reference, 1e-9) << "scale " << scale;
  }
}

TEST(ConformalModule, TwoTriangulationsAgree) {
  const double grid = module_of(annulus_with_faces(8000));
  const double rings = module_of(make_annulus(40, 400, kInner, kOuter));
  EXPECT_NEAR(rings, grid, 0.01 * grid);
}

TEST(ConformalModule, RectangleAspectRatio) {
  const int nx = 60, ny = 24;
  const double a = 2.5, b = 1.0;
  const Mesh grid = make_planar_grid(nx, ny, a, b);
  ModuleOptions options;
  const int corner_01 = nx, corner_11 = ny * (nx + 1) + nx, corner_10 = ny * (nx + 1);
  options.corners = {0, corner_01, corner_11, corner_10};
  const ModuleResult flat = conformal_module(grid, options);
  ASSERT_TRUE(flat.converged) << flat.message;
  EXPECT_EQ(flat.kind, ModuleKind::Rectangle);
  EXPECT_NEAR(flat.values[0], b / a, 1e-6);
  EXPECT_LT(flat.roundness, 1e-6);
  // Any cyclic order of the same corners gives the same rectangle.
  options.corners = {corner_11, 0, corner_10, corner_01};
  EXPECT_NEAR(conformal_module(grid, options).values[0], b / a, 1e-6);
  // Corners given from (a, 0): width b, height a.
  options.corners = {corner_01, corner_11, corner_10, 0};
  EXPECT_NEAR(conformal_module(grid, options).values[0], a / b, 1e-6);
  // Default corners: a quarter of the boundary apart from vertex 0, the square's corners.
  EXPECT_NEAR(conformal_module(make_planar_grid(16, 16, 1, 1)).values[0], 1.0, 1e-6);
  // Rolled isometrically onto a cylinder of radius 1 (the strip's width a < 2π).
  options.corners = {0, corner_01, corner_11, corner_10};
  const Mesh rolled = testing::mapped(grid, [](const Eigen::Vector3d& p) {
    return Eigen::Vector3d(std::sin(p.x()), p.y(), 1 - std::cos(p.x()));
  });
  const ModuleResult bent = conformal_module(rolled, options);
  ASSERT_TRUE(bent.converged) << bent.message;
  EXPECT_NEAR(bent.values[0], b / a, 1e-3);
}

TEST(ConformalModule, TorusOfRevolution) {
  // (R + r cos v) du and r dv: conformal coordinates u and ∫ r / (R + r cos v) dv, whose period
  // is 2π r / sqrt(R² - r²); so τ = i sqrt(R²/r² - 1), already reduced when R² >= 2 r².
  const double R = 2.0, r = 0.7;
  const ModuleResult result = conformal_module(testing::torus(160, 64, R, r));
  ASSERT_TRUE(result.converged) << result.message;
  ASSERT_EQ(result.kind, ModuleKind::FlatTorus);
  ASSERT_EQ(result.values.size(), 2u);
  std::cout << "tau " << result.values[0] << " " << result.values[1] << " exact "
            << std::sqrt(R * R / (r * r) - 1) << "\n";
  EXPECT_NEAR(result.values[0], 0.0, 1e-6);
  EXPECT_NEAR(result.values[1], std::sqrt(R * R / (r * r) - 1), 2e-3);
}

TEST(ConformalModule, BadInput) {
  ModuleOptions annulus;
  annulus.force_kind = true;
  annulus.kind = ModuleKind::Annulus;
  EXPECT_THROW((void)conformal_module(testing::sphere(2), annulus), InvalidInputError);
  EXPECT_THROW((void)conformal_module(make_open_genus(1, 1), annulus), InvalidInputError);
  ModuleOptions corners;
  corners.corners = {0, 1, 2};
  const Mesh square = make_planar_grid(4, 4, 1, 1);
  EXPECT_THROW((void)conformal_module(square, corners), InvalidInputError);
  corners.corners = {0, 4, 24, 12};  // 12 is the grid's centre
  EXPECT_THROW((void)conformal_module(square, corners), InvalidInputError);
  corners.corners = {0, 4, 24, 99};
  EXPECT_THROW((void)conformal_module(square, corners), InvalidInputError);
  corners.corners = {0, 4, 24, 4};
  EXPECT_THROW((void)conformal_module(square, corners), InvalidInputError);
  EXPECT_THROW((void)conformal_module(annulus_with_faces(500), corners), InvalidInputError);
  try {
    (void)conformal_module(testing::sphere(2), annulus);
  } catch (const InvalidInputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "the annulus module needs a genus-0 surface with two boundary loops; the mesh is "
              "genus 0 with 0 boundary loops");
  }
}

TEST(ConformalModule, SphereHasNoModule) {
  const ModuleResult result = conformal_module(testing::sphere(2));
  EXPECT_EQ(result.kind, ModuleKind::Sphere);
  EXPECT_TRUE(result.values.empty());
}

TEST(ModuleDistance, SameKindOnly) {
  ModuleResult a, b;
  a.kind = b.kind = ModuleKind::FlatTorus;
  a.values = {0.0, 1.0};
  b.values = {0.3, 1.4};
  EXPECT_NEAR(module_distance(a, b), 0.5, 1e-15);
  b.kind = ModuleKind::Annulus;
  EXPECT_THROW((void)module_distance(a, b), InvalidInputError);
}

}  // namespace
}  // namespace ricci

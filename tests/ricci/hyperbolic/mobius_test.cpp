// Möbius maps of the disk, the Klein model and the group-element enumeration.
#include <random>

#include <gtest/gtest.h>
#include <Eigen/LU>

#include <ricci/hyperbolic/klein.h>
#include <ricci/hyperbolic/mobius.h>
#include <ricci/hyperbolic/universal_cover.h>

namespace ricci {
namespace {

std::vector<Mobius> random_isometries(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), radius(0.0, 0.95);
  std::vector<Mobius> maps;
  for (int i = 0; i < count; ++i) {
    maps.push_back(Mobius::from_rotation_point(angle(rng), std::polar(radius(rng), angle(rng))));
  }
  return maps;
}

TEST(Mobius, RotationPointFormRoundTripsAndActsAsDefined) {
  for (const Mobius& m : random_isometries(50, 1)) {
    const Mobius back = Mobius::from_rotation_point(m.theta(), m.z0());
    EXPECT_LT(mobius_distance(m, back), 1e-12);
    EXPECT_NEAR(std::abs(m.m.determinant() - 1.0), 0.0, 1e-12);
    // SU(1,1): d = conj a, c = conj b.
    EXPECT_LT(std::abs(m.m(1, 1) - std::conj(m.m(0, 0))), 1e-12);
    EXPECT_LT(std::abs(m.m(1, 0) - std::conj(m.m(0, 1))), 1e-12);
    const Complex z(0.3, -0.2);
    const Complex expected =
        std::polar(1.0, m.theta()) * (z - m.z0()) / (1.0 - std::conj(m.z0()) * z);
    EXPECT_LT(std::abs(m(z) - expected), 1e-12);
  }
}

TEST(Mobius, IsometriesPreserveDiskDistanceAndCompose) {
  const auto maps = random_isometries(20, 2);
  const Complex z(0.5, 0.1), w(-0.3, 0.6);
  for (size_t i = 0; i + 1 < maps.size(); ++i) {
    EXPECT_NEAR(disk_distance(maps[i](z), maps[i](w)), disk_distance(z, w), 1e-11);
    EXPECT_LT(std::abs((maps[i] * maps[i + 1])(z) - maps[i](maps[i + 1](z))), 1e-12);
    EXPECT_LT(distance_to_identity(maps[i] * maps[i].inverse()), 1e-12);
  }
}

TEST(Mobius, ToCentreMovesTheEdgeOntoThePositiveAxis) {
  const Complex p(0.7, 0.5), q(-0.2, 0.65);
  const Mobius t = disk_to_centre(p, q);
  EXPECT_LT(std::abs(t(p)), 1e-14);
  EXPECT_LT(std::abs(t(q).imag()), 1e-14);
  EXPECT_GT(t(q).real(), 0);
  EXPECT_NEAR(t(q).real(), disk_radius(disk_distance(p, q)), 1e-13);
  const Mobius e = plane_to_centre(Complex(3, 4), Complex(1, 1));
  EXPECT_LT(std::abs(e(Complex(3, 4))), 1e-14);
  EXPECT_NEAR(e(Complex(1, 1)).real(), std::sqrt(13.0), 1e-14);
}

TEST(Klein, LorentzMatricesPreserveTheMinkowskiFormAndMatchTheMobiusAction) {
  const Eigen::Matrix3d J = Eigen::Vector3d(1, -1, -1).asDiagonal();
  for (const Mobius& m : random_isometries(30, 3)) {
    const Eigen::Matrix3d L = lorentz_matrix(m);
    EXPECT_LT((L.transpose() * J * L - J).norm(), 1e-9 * L.squaredNorm());
    EXPECT_GT(L(0, 0), 0);  // time orientation kept (SO+)
    EXPECT_NEAR(L.determinant(), 1.0, 1e-9 * L.squaredNorm());
    for (const Complex z : {Complex(0, 0), Complex(0.4, -0.3), Complex(-0.8, 0.1)}) {
      const Eigen::Vector3d x = hyperboloid_from_poincare(z);
      EXPECT_LT((L * x - hyperboloid_from_poincare(m(z))).norm(), 1e-10 * x[0] * L(0, 0));
      EXPECT_LT(std::abs(apply_projective(L, klein_from_poincare(z)) - klein_from_poincare(m(z))),
                1e-12);
    }
  }
  // Composition is kept (a homomorphism SU(1,1) -> SO+(2,1)).
  const auto maps = random_isometries(2, 4);
  EXPECT_LT((lorentz_matrix(maps[0] * maps[1]) - lorentz_matrix(maps[0]) * lorentz_matrix(maps[1])).norm(),
            1e-9 * lorentz_matrix(maps[0] * maps[1]).norm());
  for (const Complex k : {Complex(0.3, 0.2), Complex(-0.9, 0.05)}) {
    EXPECT_LT(std::abs(klein_from_poincare(poincare_from_klein(k)) - k), 1e-14);
  }
}

TEST(UniversalCover, FreeGroupCountsAndDeduplication) {
  // Two hyperbolic translations far apart generate a free group: 1 + 4 + 12 words up to length 2.
  const Mobius a = Mobius::from_rotation_point(0.0, 0.9), b = Mobius::from_rotation_point(0.0, Complex(0, 0.9));
  EXPECT_EQ(group_elements({a, b}, 2).size(), 17u);
  // A rotation by 2π/5 generates a cyclic group of order 5.
  EXPECT_EQ(group_elements({Mobius::from_rotation_point(2 * M_PI / 5, 0.0)}, 6).size(), 5u);
}

}  // namespace
}  // namespace ricci

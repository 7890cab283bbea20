// The algebraic sphere of oriented points (core/mesh/algebraic_sphere.h): spheres, concave
// spheres and planes come back from samples of them; degenerate input is refused.
#include "core/mesh/algebraic_sphere.h"

#include <cmath>
#include <random>
#include <vector>

#include "gtest/gtest.h"

namespace membrane {
namespace {

// A band of a sphere of `radius` around `centre`: the points between polar angles `from` and
// `to` (radians) from the +z pole, with the normals pointing away from the centre, or toward
// it when `inward`.
void SphereBand(const Vec3d& centre, double radius, double from, double to, bool inward,
                std::vector<Vec3d>& positions, std::vector<Vec3d>& normals) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < 500; ++i) {
    const double polar = from + (to - from) * u(rng), azimuth = 2 * M_PI * u(rng);
    const Vec3d d{std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth),
                  std::cos(polar)};
    positions.push_back(centre + radius * d);
    normals.push_back(inward ? -1.0 * d : d);
  }
}

TEST(AlgebraicSphere, BandOfASphereGivesTheSphere) {
  std::vector<Vec3d> positions, normals;
  const Vec3d centre{100, -40, 7};
  SphereBand(centre, 20, 0.6, 0.9, false, positions, normals);
  const auto sphere = AlgebraicSphere::Fit(positions, normals);
  ASSERT_TRUE(sphere.has_value());
  EXPECT_NEAR(sphere->radius(), 20, 1e-6);
  // The pole, across the hole the band leaves, and points off the sphere.
  EXPECT_NEAR(sphere->Distance(centre + Vec3d{0, 0, 20}), 0, 1e-6);
  EXPECT_NEAR(sphere->Distance(centre + Vec3d{0, 0, 23}), 3, 1e-6);
  EXPECT_NEAR(sphere->Distance(centre + Vec3d{0, 15, 0}), 5, 1e-6);
}

TEST(AlgebraicSphere, InwardNormalsGiveAConcaveSphere) {
  std::vector<Vec3d> positions, normals;
  SphereBand({0, 0, 0}, 8, 0.3, 0.7, true, positions, normals);
  const auto sphere = AlgebraicSphere::Fit(positions, normals);
  ASSERT_TRUE(sphere.has_value());
  EXPECT_NEAR(sphere->radius(), -8, 1e-6);
  EXPECT_NEAR(sphere->Distance({0, 0, 8}), 0, 1e-6);
}

TEST(AlgebraicSphere, PlaneGivesThePlane) {
  std::vector<Vec3d> positions, normals;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) {
      positions.push_back({static_cast<double>(i), static_cast<double>(j), 2.0});
      normals.push_back({0, 0, 1});
    }
  const auto sphere = AlgebraicSphere::Fit(positions, normals);
  ASSERT_TRUE(sphere.has_value());
  EXPECT_EQ(sphere->radius(), 0);
  EXPECT_NEAR(sphere->Distance({50, -30, 5}), 3, 1e-9);
  EXPECT_NEAR(sphere->Distance({4, 4, 2}), 0, 1e-9);
}

TEST(AlgebraicSphere, RefusesDegenerateInput) {
  const std::vector<Vec3d> one_point(5, Vec3d{1, 2, 3});
  const std::vector<Vec3d> up(5, Vec3d{0, 0, 1});
  EXPECT_FALSE(AlgebraicSphere::Fit(one_point, up).has_value());
  EXPECT_FALSE(AlgebraicSphere::Fit({}, {}).has_value());
  const std::vector<Vec3d> two{{0, 0, 0}, {1, 0, 0}};
  EXPECT_FALSE(AlgebraicSphere::Fit(two, up).has_value());  // counts differ
}

}  // namespace
}  // namespace membrane

// The density ratio shows as the points-per-area ratio of the densest and sparsest tenths.
#include <array>
#include <cmath>

#include "core/synth/density_ramp.h"
#include "core/synth/synth_layout.h"
#include "core/synth/synthesize.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

// Points of a unit-sphere cloud in ten slabs of equal height along `direction`. On a sphere
// equal-height slabs have equal areas (Archimedes), so counts compare densities.
std::array<int, 10> TenthCounts(const PointCloud& cloud, const Vec3d& direction) {
  std::array<int, 10> tenth{};
  for (const Point3f& p : cloud.points) {
    const double t = Dot({p[0], p[1], p[2]}, direction);
    ++tenth[std::clamp(static_cast<int>((t + 1) * 5), 0, 9)];
  }
  return tenth;
}

class DensityRatioTest : public ::testing::TestWithParam<double> {};

TEST_P(DensityRatioTest, DensestTenthOverSparsestTenthMatchesTheRatioWithin30Percent) {
  const SynthOptions options{
      .shape = "sphere", .points = 400000, .density_ratio = GetParam(), .seed = 3};
  const absl::StatusOr<PointCloud> cloud = SynthesizeShape(options);
  const absl::StatusOr<SynthLayout> layout = SynthesizeLayout(options);
  ASSERT_TRUE(cloud.ok() && layout.ok());
  ASSERT_EQ(cloud->points.size(), 400000u);
  const std::array<int, 10> tenth = TenthCounts(*cloud, layout->density_direction);
  ASSERT_GT(tenth[0], 0);
  const double measured = static_cast<double>(tenth[9]) / tenth[0];
  EXPECT_NEAR(measured, GetParam(), 0.3 * GetParam());
  // And the density grows monotonically in between (up to sampling noise).
  for (int i = 1; i < 10; ++i) EXPECT_GT(tenth[i], 0.9 * tenth[i - 1]) << "tenth " << i;
}

INSTANTIATE_TEST_SUITE_P(Ratios, DensityRatioTest, ::testing::Values(2.0, 10.0, 100.0));

TEST(DensityRatioTest, RatioOneGivesUniformTenths) {
  const SynthOptions options{.shape = "sphere", .points = 200000, .seed = 3};
  const absl::StatusOr<PointCloud> cloud = SynthesizeShape(options);
  const absl::StatusOr<SynthLayout> layout = SynthesizeLayout(options);
  ASSERT_TRUE(cloud.ok() && layout.ok());
  for (int count : TenthCounts(*cloud, layout->density_direction)) EXPECT_NEAR(count, 20000, 600);
}

TEST(DensityRatioTest, DirectionDependsOnTheSeedNotOnThePointCount) {
  const absl::StatusOr<SynthLayout> a = SynthesizeLayout({.shape = "torus", .points = 10, .seed = 5});
  const absl::StatusOr<SynthLayout> b =
      SynthesizeLayout({.shape = "torus", .points = 999, .density_ratio = 9, .seed = 5});
  const absl::StatusOr<SynthLayout> c = SynthesizeLayout({.shape = "torus", .points = 10, .seed = 6});
  ASSERT_TRUE(a.ok() && b.ok() && c.ok());
  EXPECT_EQ(a->density_direction, b->density_direction);
  EXPECT_NE(a->density_direction, c->density_direction);
  EXPECT_NEAR(Norm(a->density_direction), 1.0, 1e-12);
}

TEST(DensityRampTest, AcceptanceIsFlatOnTheOuterTenthsAndGeometricBetween) {
  const DensityRamp ramp({0, 0, 1}, {-1, 1}, 100);
  EXPECT_DOUBLE_EQ(ramp.Acceptance({0, 0, -1}), 0.01);
  EXPECT_DOUBLE_EQ(ramp.Acceptance({0, 0, -0.85}), 0.01);
  EXPECT_DOUBLE_EQ(ramp.Acceptance({0, 0, 0.85}), 1.0);
  EXPECT_DOUBLE_EQ(ramp.Acceptance({0, 0, 5}), 1.0);
  EXPECT_NEAR(ramp.Acceptance({0, 0, 0}), 0.1, 1e-12);  // halfway: sqrt(1/100)
  EXPECT_DOUBLE_EQ(DensityRamp({1, 0, 0}, {-1, 1}, 1).Acceptance({-1, 0, 0}), 1.0);
}

}  // namespace
}  // namespace membrane

// Counts, reproducibility and the geometry of the smooth shapes.
#include "core/synth/synthesize.h"

#include <cmath>
#include <string>

#include "core/synth/sphere_surfaces.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

double Radius(const Point3f& p) { return std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]); }

class EveryShapeTest : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryShapeTest, GivesExactlyTheRequestedPointCount) {
  for (int64_t n : {int64_t{12345}, int64_t{100000}}) {
    const absl::StatusOr<PointCloud> cloud = SynthesizeShape({.shape = GetParam(), .points = n});
    ASSERT_TRUE(cloud.ok()) << cloud.status();
    EXPECT_EQ(static_cast<int64_t>(cloud->points.size()), n);
  }
}

TEST_P(EveryShapeTest, SameSeedGivesTheSameCloud) {
  const SynthOptions options{.shape = GetParam(), .points = 20000, .seed = 7};
  const absl::StatusOr<PointCloud> a = SynthesizeShape(options);
  const absl::StatusOr<PointCloud> b = SynthesizeShape(options);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->points, b->points);
}

TEST_P(EveryShapeTest, DifferentSeedGivesADifferentCloud) {
  const absl::StatusOr<PointCloud> a =
      SynthesizeShape({.shape = GetParam(), .points = 20000, .seed = 7});
  const absl::StatusOr<PointCloud> b =
      SynthesizeShape({.shape = GetParam(), .points = 20000, .seed = 8});
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_NE(a->points, b->points);
}

TEST_P(EveryShapeTest, IsCentredNearTheOriginAndAboutTwoUnitsAcross) {
  const absl::StatusOr<PointCloud> cloud = SynthesizeShape({.shape = GetParam()});
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  for (int d = 0; d < 3; ++d) {
    float lo = cloud->points[0][d], hi = lo;
    for (const Point3f& p : cloud->points) lo = std::min(lo, p[d]), hi = std::max(hi, p[d]);
    EXPECT_GT(hi - lo, 1.8) << "axis " << d;
    EXPECT_LT(hi - lo, 3.4) << "axis " << d;
    EXPECT_LT(std::abs(hi + lo) / 2, 0.1) << "axis " << d;
  }
}

INSTANTIATE_TEST_SUITE_P(Shapes, EveryShapeTest, ::testing::ValuesIn(SynthShapeNames()),
                         [](const auto& info) {
                           std::string name = info.param;
                           std::erase(name, '-');
                           return name;
                         });

class SmoothShapeTest : public ::testing::TestWithParam<std::string> {};

TEST_P(SmoothShapeTest, CountStaysExactWithHolesDensityRatioAndNoise) {
  const absl::StatusOr<PointCloud> cloud = SynthesizeShape(
      {.shape = GetParam(), .points = 54321, .density_ratio = 1000, .holes = 100, .noise = 0.1});
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_EQ(cloud->points.size(), 54321u);
}

INSTANTIATE_TEST_SUITE_P(Shapes, SmoothShapeTest,
                         ::testing::Values("sphere", "two-spheres", "torus", "capped-sphere"),
                         [](const auto& info) {
                           std::string name = info.param;
                           std::erase(name, '-');
                           return name;
                         });

TEST(SphereTest, PointsLieOnTheUnitSphere) {
  const absl::StatusOr<PointCloud> cloud = SynthesizeShape({.shape = "sphere", .points = 10000});
  ASSERT_TRUE(cloud.ok());
  for (const Point3f& p : cloud->points) ASSERT_NEAR(Radius(p), 1.0, 1e-6);
}

TEST(SphereTest, IsUniformByAreaSoEqualHeightSlabsHoldEqualCounts) {
  // Archimedes: slabs of equal height cut equal areas from a sphere.
  const int n = 200000;
  const absl::StatusOr<PointCloud> cloud = SynthesizeShape({.shape = "sphere", .points = n});
  ASSERT_TRUE(cloud.ok());
  int slab[10] = {};
  for (const Point3f& p : cloud->points) ++slab[std::min(9, static_cast<int>((p[2] + 1) * 5))];
  for (int count : slab) EXPECT_NEAR(count, n / 10, 0.03 * n / 10);
}

TEST(SphereTest, NoiseDisplacesAlongTheNormalWithTheRequestedSigma) {
  const double sigma = 0.02;
  const int n = 100000;
  const absl::StatusOr<PointCloud> cloud =
      SynthesizeShape({.shape = "sphere", .points = n, .noise = sigma});
  ASSERT_TRUE(cloud.ok());
  double sum = 0, sum2 = 0;
  for (const Point3f& p : cloud->points) {
    const double e = Radius(p) - 1.0;  // along the normal: all of the error is radial
    sum += e, sum2 += e * e;
  }
  EXPECT_NEAR(sum / n, 0.0, 0.001);
  EXPECT_NEAR(std::sqrt(sum2 / n), sigma, 0.03 * sigma);
}

TEST(CappedSphereTest, HasNoPointInTheCapButPointsUpToItsRim) {
  const absl::StatusOr<PointCloud> cloud =
      SynthesizeShape({.shape = "capped-sphere", .points = 100000});
  ASSERT_TRUE(cloud.ok());
  const double rim = CappedSphereMaxZ();
  EXPECT_NEAR(2 * std::sqrt(1 - rim * rim), 0.85, 0.01);  // the cap's diameter
  int near_rim = 0;
  for (const Point3f& p : cloud->points) {
    ASSERT_NEAR(Radius(p), 1.0, 1e-6);
    ASSERT_LE(p[2], rim + 1e-6);
    near_rim += p[2] > rim - 0.01;
  }
  EXPECT_GT(near_rim, 100);
}

}  // namespace
}  // namespace membrane

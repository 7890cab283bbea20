// Holes are empty circular patches of radius kHoleRadius, bordered by points.
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "core/synth/surface_holes.h"
#include "core/synth/synth_layout.h"
#include "core/synth/synth_random.h"
#include "core/synth/synthesize.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

double NearestDistance(const PointCloud& cloud, const Vec3d& q) {
  double best = std::numeric_limits<double>::infinity();
  for (const Point3f& p : cloud.points) best = std::min(best, Norm(ToVec3d(p) - q));
  return best;
}

class HolesTest : public ::testing::TestWithParam<std::string> {};

TEST_P(HolesTest, EachHoleIsAnEmptyPatchOfTheHoleRadiusBorderedByPoints) {
  const SynthOptions options{.shape = GetParam(), .points = 200000, .holes = 4, .seed = 11};
  const absl::StatusOr<PointCloud> cloud = SynthesizeShape(options);
  const absl::StatusOr<SynthLayout> layout = SynthesizeLayout(options);
  ASSERT_TRUE(cloud.ok() && layout.ok());
  ASSERT_EQ(layout->hole_centres.size(), 4u);
  for (const Vec3d& centre : layout->hole_centres) {
    const double nearest = NearestDistance(*cloud, centre);
    EXPECT_GE(nearest, kHoleRadius - 1e-5);  // float storage of the points
    EXPECT_LT(nearest, kHoleRadius + 0.03);  // a patch, not a missing region
  }
}

INSTANTIATE_TEST_SUITE_P(Shapes, HolesTest,
                         ::testing::Values("sphere", "two-spheres", "torus", "capped-sphere"),
                         [](const auto& info) {
                           std::string name = info.param;
                           std::erase(name, '-');
                           return name;
                         });

TEST(HolesTest, WithoutHolesNoPatchOfTheSphereIsEmpty) {
  const absl::StatusOr<PointCloud> cloud =
      SynthesizeShape({.shape = "sphere", .points = 100000, .seed = 11});
  ASSERT_TRUE(cloud.ok());
  std::mt19937_64 rng(99);
  for (int i = 0; i < 300; ++i) {
    const Vec3d probe = RandomUnitVector(rng);
    ASSERT_LT(NearestDistance(*cloud, probe), 0.05) << "probe " << i;
  }
}

TEST(HolesTest, HoleCentresLieOnTheSurfaceAndDependOnTheSeed) {
  const absl::StatusOr<SynthLayout> a = SynthesizeLayout({.shape = "sphere", .holes = 3, .seed = 1});
  const absl::StatusOr<SynthLayout> b = SynthesizeLayout({.shape = "sphere", .holes = 3, .seed = 2});
  ASSERT_TRUE(a.ok() && b.ok());
  for (const Vec3d& c : a->hole_centres) EXPECT_NEAR(Norm(c), 1.0, 1e-12);
  EXPECT_NE(a->hole_centres, b->hole_centres);
}

TEST(SurfaceHolesTest, RemovesExactlyThePointsWithinTheHoleRadiusOfAnyCentre) {
  // Centres out of x order, to exercise the sorted scan.
  const SurfaceHoles holes({{0.5, 0, 0}, {-0.5, 0, 0}, {0.6, 0.5, 0}});
  EXPECT_TRUE(holes.Removes({-0.5, 0.1, 0.1}));
  EXPECT_TRUE(holes.Removes({0.5 + 0.149, 0, 0}));
  EXPECT_TRUE(holes.Removes({0.6, 0.5, -0.149}));
  EXPECT_FALSE(holes.Removes({0.5 + 0.151, 0, 0}));
  EXPECT_FALSE(holes.Removes({0, 0, 0}));
  EXPECT_FALSE(SurfaceHoles({}).Removes({0, 0, 0}));
}

TEST(HolesTest, LayoutOfCubePinholesIsInvalid) {
  EXPECT_EQ(SynthesizeLayout({.shape = "cube-pinholes"}).status().code(),
            absl::StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace membrane

// torus: a genus-1 surface whose hole no axis-aligned view shows.
#include "core/synth/torus_surface.h"

#include <cmath>
#include <numbers>

#include "core/synth/synthesize.h"
#include "gtest/gtest.h"
#include "tests/synth/silhouette.h"

namespace membrane {
namespace {

constexpr double R = kTorusMajorRadius, r = kTorusMinorRadius;

// Distance of `p` from the torus's centre circle; r for a point on the surface.
double TubeDistance(const Point3f& p) {
  const Vec3d q = {p[0], p[1], p[2]};
  const double h = Dot(q, TorusAxis());
  const double radial = std::sqrt(std::max(0.0, Dot(q, q) - h * h));
  return std::hypot(radial - R, h);
}

TEST(TorusTest, TiltMakesEveryAxisViewOfTheCentreCircleNarrowerThanTheTube) {
  // Seen along e the centre circle is an ellipse of minor semi-axis R |a.e|: the tube of
  // radius r closes the hole iff R |a.e| < r.
  for (int axis = 0; axis < 3; ++axis) EXPECT_LT(R * std::abs(TorusAxis()[axis]), r - 0.04);
}

TEST(TorusTest, NoAxisSilhouetteShowsTheHole) {
  const absl::StatusOr<PointCloud> cloud = SynthesizeShape({.shape = "torus", .points = 300000});
  ASSERT_TRUE(cloud.ok());
  for (int axis = 0; axis < 3; ++axis) {
    Vec3d d = {0, 0, 0};
    d[axis] = 1;
    testing::Silhouette view(d, 1.3, 0.03);
    view.AddAll(*cloud);
    EXPECT_EQ(view.EnclosedEmptyPixels(), 0) << "axis " << axis;
  }
}

TEST(TorusTest, SilhouetteAlongItsOwnAxisShowsTheHole) {
  // The control for the test above: the same check does see a hole when there is one.
  const absl::StatusOr<PointCloud> cloud = SynthesizeShape({.shape = "torus", .points = 300000});
  ASSERT_TRUE(cloud.ok());
  testing::Silhouette view(TorusAxis(), 1.3, 0.03);
  view.AddAll(*cloud);
  // The hole is a disc of radius R - r = 0.25: about 218 pixels.
  EXPECT_GT(view.EnclosedEmptyPixels(), 150);
}

TEST(TorusTest, PointsLieOnTheTorus) {
  const absl::StatusOr<PointCloud> cloud = SynthesizeShape({.shape = "torus", .points = 20000});
  ASSERT_TRUE(cloud.ok());
  for (const Point3f& p : cloud->points) ASSERT_NEAR(TubeDistance(p), r, 1e-6);
}

TEST(TorusTest, IsUniformByAreaSoTheOuterHalfHoldsItsLargerShare) {
  // The outer half of the tube (farther from the axis than R) has area share
  // (pi R + 2 r) / (2 pi R) = 0.70, not 1/2.
  const int n = 200000;
  const absl::StatusOr<PointCloud> cloud = SynthesizeShape({.shape = "torus", .points = n});
  ASSERT_TRUE(cloud.ok());
  int outer = 0;
  for (const Point3f& p : cloud->points) {
    const Vec3d q = {p[0], p[1], p[2]};
    const double h = Dot(q, TorusAxis());
    outer += std::sqrt(Dot(q, q) - h * h) > R;
  }
  EXPECT_NEAR(static_cast<double>(outer) / n, (std::numbers::pi * R + 2 * r) / (2 * std::numbers::pi * R), 0.005);
}

}  // namespace
}  // namespace membrane

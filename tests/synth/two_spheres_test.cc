// two-spheres: separated by a 0.3 gap, yet every axis silhouette of one overlaps the other.
#include <cmath>
#include <limits>
#include <vector>

#include "core/synth/sphere_surfaces.h"
#include "core/synth/synthesize.h"
#include "gtest/gtest.h"
#include "tests/synth/silhouette.h"

namespace membrane {
namespace {

struct SplitCloud {
  PointCloud a, b;  // points nearer the first, second centre
};

SplitCloud SplitBySphere(const PointCloud& cloud) {
  const auto centres = TwoSpheresCentres();
  SplitCloud split;
  for (const Point3f& p : cloud.points) {
    const Vec3d q = {p[0], p[1], p[2]};
    (Norm(q - centres[0]) < Norm(q - centres[1]) ? split.a : split.b).points.push_back(p);
  }
  return split;
}

TEST(TwoSpheresTest, PointsLieOnTwoUnitSpheresSharingThePointsEvenly) {
  const absl::StatusOr<PointCloud> cloud = SynthesizeShape({.shape = "two-spheres"});
  ASSERT_TRUE(cloud.ok());
  const auto centres = TwoSpheresCentres();
  const SplitCloud split = SplitBySphere(*cloud);
  for (const Point3f& p : split.a.points)
    ASSERT_NEAR(Norm(ToVec3d(p) - centres[0]), 1.0, 1e-6);
  for (const Point3f& p : split.b.points)
    ASSERT_NEAR(Norm(ToVec3d(p) - centres[1]), 1.0, 1e-6);
  EXPECT_NEAR(static_cast<double>(split.a.points.size()), 50000, 1000);
}

TEST(TwoSpheresTest, SurfacesAreSeparatedByAGapOfPointThree) {
  const absl::StatusOr<PointCloud> cloud = SynthesizeShape({.shape = "two-spheres", .points = 200000});
  ASSERT_TRUE(cloud.ok());
  const SplitCloud split = SplitBySphere(*cloud);
  // Only points facing the other sphere can be nearest: keep each sphere's cap of height 0.1
  // around its point nearest the other.
  const Vec3d axis = Normalized(TwoSpheresCentres()[1] - TwoSpheresCentres()[0]);
  const auto facing = [&](const PointCloud& c, double sign) {
    std::vector<Vec3d> out;
    for (const Point3f& p : c.points) {
      const Vec3d q = {p[0], p[1], p[2]};
      if (sign * Dot(q, axis) < 0.25) out.push_back(q);
    }
    return out;
  };
  const std::vector<Vec3d> a = facing(split.a, -1), b = facing(split.b, 1);
  ASSERT_FALSE(a.empty() || b.empty());
  double gap = std::numeric_limits<double>::infinity();
  for (const Vec3d& p : a)
    for (const Vec3d& q : b) gap = std::min(gap, Norm(p - q));
  EXPECT_GE(gap, 0.3 - 1e-5);
  EXPECT_LT(gap, 0.32);
}

TEST(TwoSpheresTest, EveryAxisSilhouetteOfOneSphereOverlapsTheOther) {
  const absl::StatusOr<PointCloud> cloud = SynthesizeShape({.shape = "two-spheres"});
  ASSERT_TRUE(cloud.ok());
  const SplitCloud split = SplitBySphere(*cloud);
  for (int axis = 0; axis < 3; ++axis) {
    Vec3d d = {0, 0, 0};
    d[axis] = 1;
    testing::Silhouette a(d, 2.0, 0.02), b(d, 2.0, 0.02);
    a.AddAll(split.a);
    b.AddAll(split.b);
    EXPECT_TRUE(a.Overlaps(b)) << "axis " << axis;
    // The overlap is geometric, not a sampling accident: the projected centre distance
    // 2.3 sqrt(2/3) = 1.88 is below the sum of the radii.
    const Vec3d offset = TwoSpheresCentres()[1] - TwoSpheresCentres()[0];
    EXPECT_LT(std::sqrt(Dot(offset, offset) - offset[axis] * offset[axis]), 1.9);
  }
}

}  // namespace
}  // namespace membrane

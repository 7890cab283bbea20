#include "tests/bench/bench_clouds.h"

#include <cstdlib>

#include "core/engine/voxelization.h"
#include "core/synth/synthesize.h"
#include "gtest/gtest.h"

namespace membrane::bench {
namespace {

PointCloud Sphere(int64_t points) {
  SynthOptions o;
  o.shape = "sphere";
  o.points = points;
  o.seed = 1;
  absl::StatusOr<PointCloud> c = SynthesizeShape(o);
  EXPECT_TRUE(c.ok()) << c.status();
  return c.ok() ? *c : PointCloud{};
}

TEST(SubsampleForGridSide, FormulaOneGivesTheTargetSide) {
  const PointCloud cloud = Sphere(40000);
  absl::StatusOr<PointCloud> sub = SubsampleForGridSide(cloud, 0, 50);
  ASSERT_TRUE(sub.ok()) << sub.status();
  EXPECT_LT(sub->points.size(), cloud.points.size() / 2);
  absl::StatusOr<Voxelization> v = Voxelize(sub->points, VoxelizeOptions{});
  ASSERT_TRUE(v.ok()) << v.status();
  EXPECT_LE(std::abs(v->grid.dim(0) - 50), 1) << v->grid.dim(0);
}

TEST(SubsampleForGridSide, KeepsPointsSpreadOverTheWholeCloud) {
  const PointCloud cloud = Sphere(40000);
  absl::StatusOr<PointCloud> sub = SubsampleForGridSide(cloud, 0, 50);
  ASSERT_TRUE(sub.ok());
  // The last kept point lies in the last stretch of the input, not at its first m points.
  EXPECT_EQ(sub->points.back()[0], cloud.points.back()[0]);
}

TEST(SubsampleForGridSide, TooFewPointsIsInvalidArgument) {
  const PointCloud cloud = Sphere(2000);
  EXPECT_EQ(SubsampleForGridSide(cloud, 0, 400).status().code(),
            absl::StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace membrane::bench

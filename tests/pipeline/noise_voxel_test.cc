// The default voxel size: formula (1)'s, raised where the points' noise is over kVoxelNoiseShare
// of it (PlanGrid with NoiseAwareVoxelSize), never for a clean cloud nor for the 8-view scans of
// ../shared/data, and never when a size is given.
#include <iostream>
#include <string>

#include "absl/strings/str_cat.h"
#include "core/engine/point_noise.h"
#include "core/engine/voxelization.h"
#include "core/pipeline/memory_estimate.h"
#include "core/synth/synthesize.h"
#include "gtest/gtest.h"
#include "tests/support/shared_data.h"
#include "tests/support/shared_models.h"

namespace membrane {
namespace {

absl::StatusOr<PointCloud> Torus(double noise) {
  return SynthesizeShape(SynthOptions{.shape = "torus", .points = 300000, .noise = noise});
}

TEST(NoiseVoxelTest, ACleanCloudKeepsFormulaOnesSize) {
  const absl::StatusOr<PointCloud> cloud = Torus(0);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  const absl::StatusOr<PlannedGrid> plan = PlanGrid(*cloud, VoxelizeOptions{});
  ASSERT_TRUE(plan.ok()) << plan.status();
  EXPECT_EQ(plan->voxel_size, plan->formula_voxel_size);
  EXPECT_EQ(plan->formula_voxel_size, FormulaVoxelSize(plan->bounds, cloud->points));
  EXPECT_LT(plan->noise.sigma, 0.01 * plan->formula_voxel_size);
}

// Noise of 0.43 formula-(1) voxels (0.004 on a torus 2.6 across at 300k points): read within
// 10%, and the voxel raised to it over kVoxelNoiseShare, so the grid is 2.7 times coarser.
TEST(NoiseVoxelTest, NoiseOverTheShareRaisesTheVoxel) {
  const double sigma = 0.004;
  const absl::StatusOr<PointCloud> cloud = Torus(sigma);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  const absl::StatusOr<PlannedGrid> plan = PlanGrid(*cloud, VoxelizeOptions{});
  ASSERT_TRUE(plan.ok()) << plan.status();
  EXPECT_NEAR(plan->noise.sigma, sigma, 0.1 * sigma);
  EXPECT_GT(plan->voxel_size, 2 * plan->formula_voxel_size);
  EXPECT_DOUBLE_EQ(plan->voxel_size, plan->noise.sigma / kVoxelNoiseShare);
  EXPECT_LT(plan->voxels, absl::StatusOr<PlannedGrid>(PlanGrid(
                              *cloud, VoxelizeOptions{.voxel_size = plan->formula_voxel_size}))
                              ->voxels);
}

TEST(NoiseVoxelTest, AGivenSizeIsKeptAndNothingMeasured) {
  const absl::StatusOr<PointCloud> cloud = Torus(0.004);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  const absl::StatusOr<PlannedGrid> plan = PlanGrid(*cloud, VoxelizeOptions{.voxel_size = 0.01});
  ASSERT_TRUE(plan.ok()) << plan.status();
  EXPECT_EQ(plan->voxel_size, 0.01);
  EXPECT_EQ(plan->formula_voxel_size, 0);
  EXPECT_EQ(plan->noise.sigma, 0);
}

// The clouds of ../shared/data (8 simulated range scans with noise along the rays, and the
// variable-density samples) read 0.10-0.12 of their formula-(1) voxel at most: their default
// voxel is formula (1)'s, so their expected topology at 1x holds at the default.
TEST(NoiseVoxelTest, TheSharedScansKeepFormulaOnesSize) {
  MEMBRANE_REQUIRE_SHARED_DATA(data_dir);
  for (const testing::SharedModel& m : testing::SharedModels()) {
    for (const std::string& kind : m.kinds) {
      const std::string name = absl::StrCat(m.model, "-", kind);
      const absl::StatusOr<PointCloud> cloud = testing::ReadSharedCloud(data_dir, name);
      ASSERT_TRUE(cloud.ok()) << cloud.status();
      const absl::StatusOr<PlannedGrid> plan = PlanGrid(*cloud, VoxelizeOptions{});
      ASSERT_TRUE(plan.ok()) << plan.status();
      const double share = plan->noise.sigma / plan->formula_voxel_size;
      std::cout << name << ": noise " << share << " of the formula-(1) voxel\n";
      EXPECT_EQ(plan->voxel_size, plan->formula_voxel_size) << name << " reads " << share;
      EXPECT_GT(plan->noise.fitted_boxes, kNoiseBoxes / 2) << name;
    }
  }
}

}  // namespace
}  // namespace membrane

// The estimates the memory budget and the --local memory limit refuse jobs on.
#include <gtest/gtest.h>

#include "core/engine/voxelization.h"
#include "core/pipeline/memory_estimate.h"
#include "core/synth/synthesize.h"

namespace membrane::testing {
namespace {

TEST(PlanGrid, PlansTheGridVoxelizeAllocates) {
  absl::StatusOr<PointCloud> cloud =
      SynthesizeShape(SynthOptions{.shape = "torus", .points = 20000});
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  for (const double voxel_size : {0.0, 0.05}) {
    absl::StatusOr<PlannedGrid> plan =
        PlanGrid(*cloud, VoxelizeOptions{.voxel_size = voxel_size});
    ASSERT_TRUE(plan.ok()) << plan.status();
    absl::StatusOr<Voxelization> v =
        Voxelize(cloud->points, VoxelizeOptions{.voxel_size = voxel_size});
    ASSERT_TRUE(v.ok()) << v.status();
    EXPECT_EQ(plan->voxels, v->grid.size()) << "voxel size " << voxel_size;
    EXPECT_EQ(plan->voxel_size, v->grid.voxel_size());
    EXPECT_EQ(plan->bytes, GridBytesEstimate(v->grid.size(), 20000));
  }
}

TEST(PlanGrid, ADegenerateCloudIsInvalidArgument) {
  PointCloud flat;
  for (int i = 0; i < 100; ++i) flat.points.push_back({float(i % 10), float(i / 10), 0});
  EXPECT_EQ(PlanGrid(flat, VoxelizeOptions{}).status().code(),
            absl::StatusCode::kInvalidArgument);
}

TEST(GridBytesEstimate, SaturatesInsteadOfOverflowing) {
  EXPECT_EQ(GridBytesEstimate(1000, 10), 6000 + 480);
  EXPECT_GT(GridBytesEstimate(4'000'000'000'000'000'000, 0), int64_t{1} << 62);
}

TEST(SurfaceBytesEstimate, CountsTheBoundaryVoxels) {
  MembraneCounts counts;
  counts.hard_voxels = 10;
  counts.frozen_voxels = 20;
  counts.soft_voxels = 30;
  counts.inside_soft_voxels = 1'000'000;  // the solid's inside takes no surface
  EXPECT_EQ(SurfaceBytesEstimate(counts), 60'000);
}

TEST(BytesText, ThreeSignificantDigitsInPowersOfAThousand) {
  EXPECT_EQ(BytesText(512), "512 bytes");
  EXPECT_EQ(BytesText(999), "999 bytes");
  EXPECT_EQ(BytesText(1000), "1 KB");
  EXPECT_EQ(BytesText(38'123'456), "38.1 MB");
  EXPECT_EQ(BytesText(999'600'000), "1 GB");
  EXPECT_EQ(BytesText(2'612'345'678), "2.61 GB");
}

}  // namespace
}  // namespace membrane::testing

// A given grid box (ReconstructionOptions::grid_box): the grid is planned on it instead of the
// points' own, so that a quantized copy of a cloud gets the cloud's grid; a box that is not
// finite, flat, inverted or far from the points is refused naming grid_box.
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/pipeline/grid_box.h"
#include "core/pipeline/memory_estimate.h"
#include "core/pipeline/reconstruction_options.h"
#include "tests/support/in_memory_run.h"
#include "tests/support/plane_edge_cloud.h"

namespace membrane::testing {
namespace {

using ::testing::HasSubstr;

const Box3d kUnitBox = {{0, 0, 0}, {1, 1, 1}};

TEST(GridBox, NotFiniteFlatOrInvertedIsRefusedNamingTheAxis) {
  EXPECT_TRUE(CheckGridBox(kUnitBox).ok());
  Box3d infinite = kUnitBox;
  infinite.max[0] = INFINITY;
  EXPECT_THAT(CheckGridBox(infinite).message(), HasSubstr("grid_box x: max inf is not finite"));
  Box3d nan = kUnitBox;
  nan.min[1] = NAN;
  EXPECT_THAT(CheckGridBox(nan).message(), HasSubstr("grid_box y: min nan is not finite"));
  Box3d inverted = kUnitBox;
  inverted.min[2] = 2;
  EXPECT_EQ(CheckGridBox(inverted).code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(CheckGridBox(inverted).message(), HasSubstr("grid_box z: min 2 is not below max 1"));
  Box3d flat = kUnitBox;
  flat.max[1] = 0;
  EXPECT_THAT(CheckGridBox(flat).message(), HasSubstr("grid_box y: min 0 is not below max 0"));
}

TEST(GridBox, PointsMayLieOutsideByAnEighthOfTheVoxel) {
  Box3d points = kUnitBox;
  points.max[2] = 1.012;  // 0.012 above, at voxel 0.1: within 0.0125
  points.min[0] = -0.012;
  EXPECT_TRUE(CheckGridBoxHoldsPoints(kUnitBox, points, 0.1).ok());
  points.max[2] = 1.013;
  const absl::Status s = CheckGridBoxHoldsPoints(kUnitBox, points, 0.1);
  EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(s.message(), HasSubstr("grid_box does not contain the points: their z max 1.013 "
                                     "is 0.013 above the box's 1, more than the 0.0125 (1/8 of "
                                     "the voxel size 0.1)"));
  points.max[2] = 1;
  points.min[0] = -0.5;
  EXPECT_THAT(CheckGridBoxHoldsPoints(kUnitBox, points, 0.1).message(),
              HasSubstr("their x min -0.5 is 0.5 below the box's 0"));
}

// The plan reads the given box: its bounds and voxel count are the box's, and the points are
// still checked against it.
TEST(GridBox, PlanGridPlansOnTheGivenBox) {
  const PlaneEdgeCloud c = MakePlaneEdgeCloud(10000);
  const VoxelizeOptions voxelize{.voxel_size = c.voxel_size};
  absl::StatusOr<PlannedGrid> own = PlanGrid(c.quantized, voxelize);
  absl::StatusOr<PlannedGrid> boxed = PlanGrid(c.quantized, voxelize, CancelToken::Never(), c.box);
  absl::StatusOr<PlannedGrid> original = PlanGrid(c.cloud, voxelize);
  ASSERT_TRUE(own.ok() && boxed.ok() && original.ok());
  EXPECT_EQ(boxed->bounds.min, c.box.min);
  EXPECT_EQ(boxed->bounds.max, c.box.max);
  EXPECT_EQ(boxed->voxels, original->voxels);
  EXPECT_NE(own->voxels, original->voxels);

  Box3d far = c.box;
  far.max[1] -= c.voxel_size / 4;
  const absl::StatusOr<PlannedGrid> refused =
      PlanGrid(c.quantized, voxelize, CancelToken::Never(), far);
  EXPECT_EQ(refused.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(refused.status().message(), HasSubstr("grid_box does not contain the points"));
  Box3d inverted = c.box;
  std::swap(inverted.min[0], inverted.max[0]);
  EXPECT_THAT(PlanGrid(c.quantized, voxelize, CancelToken::Never(), inverted).status().message(),
              HasSubstr("grid_box x: min"));
}

absl::StatusOr<ReconstructionReport> Reconstruct(const PointCloud& cloud, double voxel_size,
                                                 const std::optional<Box3d>& box) {
  ReconstructionOptions options;
  options.voxelize.voxel_size = voxel_size;
  options.grid_box = box;
  return ReconstructInMemory(cloud, options);
}

// The quantized copy's own box is a plane shorter or longer; with the cloud's box its grid is
// the cloud's, and its mesh a sphere as the cloud's.
TEST(GridBox, QuantizedCopyGetsTheCloudsGridWithItsBox) {
  const PlaneEdgeCloud c = MakePlaneEdgeCloud(10000);
  const absl::StatusOr<ReconstructionReport> local = Reconstruct(c.cloud, c.voxel_size, {});
  const absl::StatusOr<ReconstructionReport> own = Reconstruct(c.quantized, c.voxel_size, {});
  const absl::StatusOr<ReconstructionReport> boxed =
      Reconstruct(c.quantized, c.voxel_size, c.box);
  ASSERT_TRUE(local.ok()) << local.status();
  ASSERT_TRUE(own.ok()) << own.status();
  ASSERT_TRUE(boxed.ok()) << boxed.status();
  EXPECT_EQ(local->data_grid, c.data_dims);
  EXPECT_EQ(own->data_grid, c.quantized_data_dims);
  EXPECT_EQ(boxed->data_grid, c.data_dims);
  EXPECT_TRUE(boxed->mesh.closed && boxed->mesh.manifold);
  EXPECT_EQ(boxed->mesh.genus, local->mesh.genus);
}

}  // namespace
}  // namespace membrane::testing

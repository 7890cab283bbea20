// The paper's density ratio (section 4.3) measured without a grid, and Voxelize's hard voxels
// built from the same voxel indices.
#include <gtest/gtest.h>

#include "core/engine/point_density.h"
#include "core/engine/voxelization.h"
#include "core/synth/synthesize.h"

namespace membrane::testing {
namespace {

TEST(MeasurePointDensity, CountsVoxelsHoldingOneAndMorePoints) {
  // Unit voxels from (0,0,0): two points in (0,0,0), one in (2,0,0), three in (1,1,1), one in
  // the last voxel (3,1,1) through the box's far corner.
  const std::vector<Point3f> points = {{0.1f, 0.1f, 0.1f}, {0.9f, 0.9f, 0.9f}, {2.5f, 0.5f, 0.5f},
                                       {1.5f, 1.5f, 1.5f}, {1.2f, 1.2f, 1.2f}, {1.9f, 1.1f, 1.3f},
                                       {3.0f, 2.0f, 2.0f}};
  const Box3d box{{0, 0, 0}, {3, 2, 2}};
  const PointDensity d = MeasurePointDensity(points, box, 1.0);
  EXPECT_EQ(d.voxels_with_one_point, 2);
  EXPECT_EQ(d.voxels_with_more_points, 2);
  EXPECT_DOUBLE_EQ(d.ratio(), 1.0);
  EXPECT_EQ(DataDims(box, 1.0), (std::array<int, 3>{4, 3, 3}));
}

TEST(MeasurePointDensity, AgreesWithVoxelize) {
  absl::StatusOr<PointCloud> cloud =
      SynthesizeShape(SynthOptions{.shape = "torus", .points = 20000, .noise = 0.02});
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  absl::StatusOr<Voxelization> v = Voxelize(cloud->points, VoxelizeOptions{});
  ASSERT_TRUE(v.ok()) << v.status();
  const PointDensity d = MeasurePointDensity(cloud->points, v->bounds, v->grid.voxel_size());
  EXPECT_EQ(d.voxels_with_one_point, v->voxels_with_one_point);
  EXPECT_EQ(d.voxels_with_more_points, v->voxels_with_more_points);
  EXPECT_EQ(d.ratio(), v->density_ratio);
  // Every voxel holding points is hard, and no other.
  int64_t hard = 0;
  for (int64_t i = 0; i < v->grid.size(); ++i) hard += IsHard(v->grid.at(i)) ? 1 : 0;
  EXPECT_EQ(hard, v->hard_voxels);
}

}  // namespace
}  // namespace membrane::testing

// SnapKeepingVoxels: the upload's positions on Draco's grid, each in the voxel of the planned
// grid its point lies in, at most a step from it, and returned exactly by a Draco decoder.
#include "client/voxel_keeping_snap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "core/engine/point_density.h"
#include "core/io/draco_codec.h"
#include "core/pipeline/grid_box.h"

namespace membrane::client {
namespace {

// `n` points spread uniformly through [0, 1] x [0, 0.6] x [0, 0.3], with the box's corners.
std::vector<Point3f> Points(int n) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> unit(0, 1);
  std::vector<Point3f> points = {{0, 0, 0}, {1, 0.6f, 0.3f}};
  for (int i = 0; i < n; ++i) {
    points.push_back({unit(random), 0.6f * unit(random), 0.3f * unit(random)});
  }
  return points;
}

const Box3d kBox = {{0, 0, 0}, {1, 0.6f, 0.3f}};

TEST(VoxelKeepingSnap, EveryPointStaysInItsVoxelWithinAStep) {
  const std::vector<Point3f> original = Points(200000);
  std::vector<Point3f> points = original;
  // 11 bits over a side of 1: a step of 1/2047, an eighth of a voxel of 1/255.
  const double voxel = 1.0 / 255;
  const std::optional<VoxelKeepingSnap> snap = SnapKeepingVoxels(points, kBox, voxel, 11);
  ASSERT_TRUE(snap.has_value());
  const std::array<int, 3> dims = DataDims(kBox, voxel);
  const double step = snap->grid.step();
  double largest = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      ASSERT_EQ(DataVoxelAlong(points[i][c], kBox.min[c], voxel, dims[c]),
                DataVoxelAlong(original[i][c], kBox.min[c], voxel, dims[c]))
          << i << " " << c;
      largest = std::max(largest, std::fabs(double{points[i][c]} - original[i][c]));
    }
    ASSERT_EQ(snap->grid.Snap(points[i]), points[i]) << i;  // already on the grid
  }
  EXPECT_LE(largest, step * 1.001);
  EXPECT_DOUBLE_EQ(snap->max_error, largest);
  // Plain rounding carries a coordinate across a face when the nearest node is across it: a
  // quarter of a step a face on average, 1/32 of the coordinates at 8 steps a voxel.
  EXPECT_GT(snap->moved_coordinates, 200000 * 3 / 32 / 2);
  EXPECT_LT(snap->moved_coordinates, 200000 * 3 / 32 * 2);
}

TEST(VoxelKeepingSnap, TheSamePositionsAndFiguresOnAnyThreadCount) {
  // Over the calling thread's share: 200,002 points are cut into ranges.
  const std::vector<Point3f> original = Points(200000);
  std::vector<Point3f> one = original;
  const std::optional<VoxelKeepingSnap> alone = SnapKeepingVoxels(one, kBox, 1.0 / 255, 11, 1);
  ASSERT_TRUE(alone.has_value());
  for (int threads : {2, 3}) {
    std::vector<Point3f> points = original;
    const std::optional<VoxelKeepingSnap> snap =
        SnapKeepingVoxels(points, kBox, 1.0 / 255, 11, threads);
    ASSERT_TRUE(snap.has_value());
    EXPECT_EQ(points, one) << threads;
    EXPECT_EQ(snap->moved_coordinates, alone->moved_coordinates) << threads;
    EXPECT_EQ(snap->max_error, alone->max_error) << threads;
  }
}

TEST(VoxelKeepingSnap, DracoReturnsTheSnappedPositions) {
  std::vector<Point3f> points = Points(20000);
  const std::optional<VoxelKeepingSnap> snap = SnapKeepingVoxels(points, kBox, 1.0 / 255, 11);
  ASSERT_TRUE(snap.has_value());
  DracoOptions draco;
  draco.position_quantization_bits = 11;
  draco.box = snap->grid.box;
  PointCloud cloud;
  cloud.points = points;
  absl::StatusOr<DracoEncoding> encoded = EncodeDracoPointCloud(cloud, draco);
  ASSERT_TRUE(encoded.ok()) << encoded.status();
  absl::StatusOr<DecodedDracoCloud> decoded = DecodeDracoPointCloud(encoded->bytes);
  ASSERT_TRUE(decoded.ok()) << decoded.status();
  std::vector<Point3f> back = decoded->cloud.points;
  std::sort(back.begin(), back.end());
  std::sort(points.begin(), points.end());
  EXPECT_EQ(back, points);
}

TEST(VoxelKeepingSnap, NoneWhenTheStepIsOverAnEighthOfTheVoxelOrLossless) {
  std::vector<Point3f> points = Points(100);
  const std::vector<Point3f> original = points;
  // 11 bits: a step of 1/2047, over an eighth of a voxel of 1/300.
  EXPECT_FALSE(SnapKeepingVoxels(points, kBox, 1.0 / 300, 11).has_value());
  EXPECT_FALSE(SnapKeepingVoxels(points, kBox, 1.0 / 255, 0).has_value());
  EXPECT_EQ(points, original);
  EXPECT_TRUE(SnapKeepingVoxels(points, kBox, 1.0 / 300, 12).has_value());
}

}  // namespace
}  // namespace membrane::client

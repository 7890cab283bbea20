// cube-pinholes: voxelized at its voxel size from its bounding-box min, the cloud makes
// exactly the one-voxel-thick wall hard, minus two pinholes lined up along x.
#include "core/synth/cube_pinholes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

#include "core/synth/synthesize.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

using Voxel = std::array<int, 3>;

// Voxelizes as core/engine does: origin at the bounding-box min, floor((p - min) / l), and
// floor(L / l) + 1 voxels per axis. Returns the points per voxel.
struct Voxelized {
  std::array<double, 3> min{};
  std::array<int, 3> dims{};
  std::array<int, 3> ceil_dims{};  // ceil(L / l): the other common convention
  std::map<Voxel, int> counts;
};

Voxelized VoxelizeLikeTheEngine(const PointCloud& cloud, double l) {
  Voxelized v;
  std::array<double, 3> max{};
  for (int d = 0; d < 3; ++d) {
    v.min[d] = max[d] = cloud.points[0][d];
    for (const Point3f& p : cloud.points) {
      v.min[d] = std::min<double>(v.min[d], p[d]);
      max[d] = std::max<double>(max[d], p[d]);
    }
    v.dims[d] = static_cast<int>(std::floor((max[d] - v.min[d]) / l)) + 1;
    v.ceil_dims[d] = static_cast<int>(std::ceil((max[d] - v.min[d]) / l));
  }
  for (const Point3f& p : cloud.points) {
    Voxel c;
    for (int d = 0; d < 3; ++d) c[d] = static_cast<int>(std::floor((p[d] - v.min[d]) / l));
    ++v.counts[c];
  }
  return v;
}

struct CubeCase {
  const char* name;
  SynthOptions options;
};

class CubePinholesTest : public ::testing::TestWithParam<CubeCase> {};

TEST_P(CubePinholesTest, VoxelizationGivesExactlyTheOpenWallVoxelsAsHard) {
  const SynthOptions& options = GetParam().options;
  const absl::StatusOr<CubePinholesGrid> grid = CubePinholesGridFor(options);
  const absl::StatusOr<PointCloud> cloud = SynthesizeShape(options);
  ASSERT_TRUE(grid.ok()) << grid.status();
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  ASSERT_EQ(static_cast<int64_t>(cloud->points.size()), options.points);

  const Voxelized v = VoxelizeLikeTheEngine(*cloud, grid->voxel_size);
  const int m = grid->side;
  for (int d = 0; d < 3; ++d) {
    EXPECT_EQ(v.min[d], grid->origin[d]) << "axis " << d;  // exactly, not approximately
    EXPECT_EQ(v.dims[d], m) << "axis " << d;
    EXPECT_EQ(v.ceil_dims[d], m) << "axis " << d;
  }
  int64_t hard = 0;
  for (const auto& [c, count] : v.counts) {
    ASSERT_TRUE(c[0] >= 0 && c[1] >= 0 && c[2] >= 0 && c[0] < m && c[1] < m && c[2] < m);
    EXPECT_TRUE(grid->IsHard(c)) << c[0] << "," << c[1] << "," << c[2];
    ++hard;
  }
  EXPECT_EQ(hard, grid->open_wall_voxels);
}

TEST_P(CubePinholesTest, EmptyWallVoxelsAreTwoHolesFacingEachOtherAlongX) {
  const SynthOptions& options = GetParam().options;
  const absl::StatusOr<CubePinholesGrid> grid = CubePinholesGridFor(options);
  const absl::StatusOr<PointCloud> cloud = SynthesizeShape(options);
  ASSERT_TRUE(grid.ok() && cloud.ok());
  const Voxelized v = VoxelizeLikeTheEngine(*cloud, grid->voxel_size);
  const int m = grid->side, k = grid->hole_size;
  std::vector<Voxel> low, high;  // empty wall voxels on x = 0 and x = m - 1
  for (int z = 0; z < m; ++z)
    for (int y = 0; y < m; ++y)
      for (int x = 0; x < m; ++x) {
        const Voxel c = {x, y, z};
        if (!grid->IsWall(c) || v.counts.contains(c)) continue;
        ASSERT_TRUE(x == 0 || x == m - 1) << "empty wall voxel " << x << "," << y << "," << z;
        (x == 0 ? low : high).push_back(c);
      }
  ASSERT_EQ(low.size(), static_cast<size_t>(k * k));
  ASSERT_EQ(high.size(), static_cast<size_t>(k * k));
  for (size_t i = 0; i < low.size(); ++i) {
    EXPECT_EQ(low[i][1], high[i][1]);
    EXPECT_EQ(low[i][2], high[i][2]);
    // Away from the wall's edges, so each hole is surrounded by hard wall voxels.
    for (int d = 1; d < 3; ++d) EXPECT_TRUE(low[i][d] >= 1 && low[i][d] <= m - 2);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, CubePinholesTest,
    ::testing::Values(
        CubeCase{"AutomaticVoxelSize", {.shape = "cube-pinholes", .points = 100000}},
        CubeCase{"GivenVoxelSize",
                 {.shape = "cube-pinholes", .points = 30000, .seed = 4, .voxel_size = 0.1}},
        CubeCase{"OddVoxelSizeAndThreeByThreeHoles",
                 {.shape = "cube-pinholes",
                  .points = 50000,
                  .seed = 9,
                  .voxel_size = 0.0371,
                  .hole_size = 3}},
        CubeCase{"SmallestCube",
                 {.shape = "cube-pinholes", .points = 26, .voxel_size = 1, .hole_size = 1}}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(CubePinholesTest, AutomaticVoxelSizeGivesFourToFivePointsPerWallVoxel) {
  const SynthOptions options{.shape = "cube-pinholes", .points = 100000};
  const absl::StatusOr<CubePinholesGrid> grid = CubePinholesGridFor(options);
  const absl::StatusOr<PointCloud> cloud = SynthesizeShape(options);
  ASSERT_TRUE(grid.ok() && cloud.ok());
  EXPECT_NEAR(grid->voxel_size * grid->side, 2.0, 1e-12);
  const Voxelized v = VoxelizeLikeTheEngine(*cloud, grid->voxel_size);
  for (const auto& [c, count] : v.counts) {
    ASSERT_GE(count, 4);
    ASSERT_LE(count, 5);
  }
}

TEST(CubePinholesTest, GivenVoxelSizeMakesACubeAboutTwoUnitsAcross) {
  const absl::StatusOr<CubePinholesGrid> grid =
      CubePinholesGridFor({.shape = "cube-pinholes", .voxel_size = 0.05});
  ASSERT_TRUE(grid.ok());
  EXPECT_EQ(grid->side, 40);
  EXPECT_EQ(grid->voxel_size, 0.05);
  EXPECT_EQ(grid->hole_lo, 19);
  EXPECT_EQ(grid->open_wall_voxels, 40 * 40 * 40 - 38 * 38 * 38 - 2);
}

}  // namespace
}  // namespace membrane

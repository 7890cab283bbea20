#include "core/mesh/voxel_boundary.h"

#include <array>
#include <cstdint>
#include <random>
#include <string>

#include "core/engine/voxel_grid.h"
#include "core/engine/voxel_state.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

// A grid of the given size whose voxels off the outer layer are solid with probability p:
// every corner configuration, split fans and edge midpoints in every layer, up to the
// layers next to the array's border.
VoxelGrid RandomBoxGrid(std::array<int, 3> dims, double p, uint32_t seed) {
  VoxelGrid grid(dims, {0, 0, 0}, 1.0, OutsideState(0));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  for (int z = 1; z < dims[2] - 1; ++z)
    for (int y = 1; y < dims[1] - 1; ++y)
      for (int x = 1; x < dims[0] - 1; ++x)
        if (u(rng) < p) grid.set(Coord{x, y, z}, kInsideSoft);
  return grid;
}

// Field by field: the slabs must give the one-thread pass's numbering, not just its mesh.
void ExpectSameBoundary(const VoxelBoundary& a, const VoxelBoundary& b, const std::string& what) {
  ASSERT_EQ(a.fan_vertices.size(), b.fan_vertices.size()) << what;
  ASSERT_EQ(a.midpoints.size(), b.midpoints.size()) << what;
  ASSERT_EQ(a.quads.size(), b.quads.size()) << what;
  EXPECT_EQ(a.corner_contacts, b.corner_contacts) << what;
  for (size_t i = 0; i < a.fan_vertices.size(); ++i) {
    const auto &u = a.fan_vertices[i], &v = b.fan_vertices[i];
    ASSERT_TRUE(u.corner == v.corner && u.config == v.config && u.fan == v.fan)
        << what << ", fan vertex " << i;
  }
  for (size_t i = 0; i < a.midpoints.size(); ++i) {
    const auto &u = a.midpoints[i], &v = b.midpoints[i];
    ASSERT_TRUE(u.ends == v.ends && u.edge_start == v.edge_start && u.axis == v.axis &&
                u.outside == v.outside)
        << what << ", midpoint " << i;
  }
  for (size_t i = 0; i < a.quads.size(); ++i) {
    const auto &u = a.quads[i], &v = b.quads[i];
    ASSERT_TRUE(u.solid == v.solid && u.axis == v.axis && u.positive == v.positive &&
                u.corners == v.corners && u.midpoints == v.midpoints)
        << what << ", quad " << i;
  }
}

TEST(VoxelBoundary, SlabsGiveTheOneThreadPassesNumbering) {
  // Random boxes from 3 voxels a side, on 1 and 3 threads and 1, 2, 5 slabs and one a layer.
  std::mt19937 rng(7);
  int with_midpoints = 0;
  for (int trial = 0; trial < 120; ++trial) {
    std::uniform_int_distribution<int> side(3, trial < 60 ? 9 : 30);
    const std::array<int, 3> dims{side(rng), side(rng), side(rng)};
    const double p = std::uniform_real_distribution<double>(0.1, 0.7)(rng);
    const VoxelGrid grid = RandomBoxGrid(dims, p, static_cast<uint32_t>(trial));
    const VoxelBoundary one = ExtractVoxelBoundary(grid, 1);
    if (!one.midpoints.empty()) ++with_midpoints;
    for (int threads : {1, 3})
      for (int slabs : {1, 2, 5, dims[2]}) {
        const std::string what = "trial " + std::to_string(trial) + ", " +
                                 std::to_string(threads) + " threads, " +
                                 std::to_string(slabs) + " slabs";
        ExpectSameBoundary(ExtractVoxelBoundaryOnSlabs(grid, threads, slabs), one, what);
        if (HasFatalFailure()) return;
      }
  }
  EXPECT_GT(with_midpoints, 30);  // the slabs' shared midpoints were exercised
}

TEST(VoxelBoundary, ThreadedPassOnALargeGridIsTheOneThreadPass) {
  // 2^24 voxels and more: ExtractVoxelBoundary itself takes the slabs on 2 threads or more.
  const VoxelGrid grid = RandomBoxGrid({260, 256, 258}, 0.02, 11);
  ASSERT_GE(grid.size(), int64_t{1} << 24);
  const VoxelBoundary one = ExtractVoxelBoundary(grid, 1);
  ExpectSameBoundary(ExtractVoxelBoundary(grid, 3), one, "3 threads");
}

}  // namespace
}  // namespace membrane

// Paper section 7's post-process: inside hard voxels are connected to the membrane where a
// path of soft voxels leads out, and left where none does, without changing the topology.
#include <gtest/gtest.h>

#include "core/engine/membrane_invariants.h"
#include "core/engine/post_process.h"
#include "core/engine/voxel_topology.h"

namespace membrane {
namespace {

// A final membrane of a hollow box of `n`^3 voxels (padding around): its outer layer boundary
// hard, the layer below it inside hard (a thick scanned wall), and a sealed interior of
// inside soft voxels. The inside hard layer's voxels face the interior and nothing else.
VoxelGrid HollowBox(int n) {
  const int p = VoxelGrid::kPadding;
  const int dim = n + 2 * p;
  VoxelGrid grid({dim, dim, dim}, {0, 0, 0}, 1.0, OutsideState(0));
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const int layer = std::min({x, y, z, n - 1 - x, n - 1 - y, n - 1 - z});
        grid.set(grid.Index(x + p, y + p, z + p),
                 layer == 0 ? kBoundaryHard : layer == 1 ? kInsideHard : kInsideSoft);
      }
  return grid;
}

int64_t CountState(const VoxelGrid& grid, VoxelState state) {
  return std::count(grid.states().begin(), grid.states().end(), state);
}

TEST(ConnectInsideHardVoxels, ASealedInteriorLeavesTheWallAsItIs) {
  VoxelGrid grid = HollowBox(20);
  const VoxelStates before = grid.states();
  absl::StatusOr<PostProcessStats> stats = ConnectInsideHardVoxels(grid, CancelToken::Never());
  ASSERT_TRUE(stats.ok()) << stats.status();
  EXPECT_EQ(stats->inside_hard_before, 18 * 18 * 18 - 16 * 16 * 16);
  EXPECT_EQ(stats->inside_hard_after, stats->inside_hard_before);
  EXPECT_EQ(stats->carved_voxels, 0);
  EXPECT_EQ(grid.states(), before);
}

// An interior wider than the search's reach (64 steps, 200k voxels): each wall voxel's search
// is cut short, and the interior is then flooded once and known sealed. Without that, each of
// the 100k wall voxels would search 200k voxels of it again (hours).
TEST(ConnectInsideHardVoxels, AWideSealedInteriorEnds) {
  VoxelGrid grid = HollowBox(140);
  absl::StatusOr<PostProcessStats> stats = ConnectInsideHardVoxels(grid, CancelToken::Never());
  ASSERT_TRUE(stats.ok()) << stats.status();
  EXPECT_EQ(stats->inside_hard_after, stats->inside_hard_before);
  EXPECT_EQ(stats->carved_voxels, 0);
}

// The same wide interior with an opening: it leads out, so it is not skipped, and most wall
// voxels are farther than 64 steps from the opening. Their searches are cut short one after the
// other; all searches together stop at 4 visits per grid voxel, leaving the rest (counted).
TEST(ConnectInsideHardVoxels, AWideInteriorOpenFarAwayEndsWithinTheBudget) {
  const int n = 140, p = VoxelGrid::kPadding;
  VoxelGrid grid = HollowBox(n);
  grid.set(grid.Index(n / 2 + p, n / 2 + p, p), kBoundaryFrozen);
  grid.set(grid.Index(n / 2 + p, n / 2 + p, p + 1), kBoundarySoft);
  absl::StatusOr<PostProcessStats> stats = ConnectInsideHardVoxels(grid, CancelToken::Never());
  ASSERT_TRUE(stats.ok()) << stats.status();
  EXPECT_GT(stats->inside_hard_after, 0);
  EXPECT_EQ(stats->inside_hard_after, CountState(grid, kInsideHard));
  EXPECT_TRUE(CheckMembraneInvariants(grid, InvariantOptions{}).ok())
      << CheckMembraneInvariants(grid, InvariantOptions{});
}

// A soft voxel in the outer layer opens the interior to the outside: the wall voxels near it
// are connected by carving, the rest stay, and the solid keeps one shell of genus 0.
TEST(ConnectInsideHardVoxels, AnOpeningConnectsTheWallNearItAndKeepsTheTopology) {
  const int n = 20, p = VoxelGrid::kPadding;
  VoxelGrid grid = HollowBox(n);
  grid.set(grid.Index(n / 2 + p, n / 2 + p, p), kBoundaryFrozen);      // the opening
  grid.set(grid.Index(n / 2 + p, n / 2 + p, p + 1), kBoundarySoft);    // under it
  const VoxelTopology topology_before = ComputeVoxelTopology(grid);
  absl::StatusOr<PostProcessStats> stats = ConnectInsideHardVoxels(grid, CancelToken::Never());
  ASSERT_TRUE(stats.ok()) << stats.status();
  EXPECT_GT(stats->carved_voxels, 0);
  EXPECT_LT(stats->inside_hard_after, stats->inside_hard_before);
  EXPECT_EQ(stats->inside_hard_after, CountState(grid, kInsideHard));
  const VoxelTopology topology_after = ComputeVoxelTopology(grid);
  EXPECT_EQ(topology_after.shells, topology_before.shells);
  EXPECT_EQ(topology_after.genus, topology_before.genus);
  EXPECT_TRUE(CheckMembraneInvariants(grid, InvariantOptions{}).ok())
      << CheckMembraneInvariants(grid, InvariantOptions{});
}

}  // namespace
}  // namespace membrane

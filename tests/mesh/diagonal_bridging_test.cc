#include "core/mesh/diagonal_bridging.h"

#include "core/engine/voxel_topology.h"
#include "gtest/gtest.h"
#include "tests/mesh/test_grids.h"

namespace membrane {
namespace {

using namespace membrane::testing;

TEST(DiagonalBridging, JoinsTwoVoxelsMeetingAtACorner) {
  VoxelGrid g = CornerContactGrid();
  const BridgingResult r = BridgeDiagonalContacts(g);
  EXPECT_EQ(r.added, 1);
  EXPECT_EQ(r.remaining, 0);
  const VoxelTopology t = ComputeVoxelTopology(g);
  EXPECT_EQ(t.shells, 1);
  EXPECT_EQ(t.genus, std::vector<int>{0});
}

TEST(DiagonalBridging, LeavesEdgeContactsAlone) {
  VoxelGrid g = EdgeContactGrid();
  EXPECT_EQ(BridgeDiagonalContacts(g).added, 0);
}

TEST(DiagonalBridging, NeverChangesTopologyOfRandomSolids) {
  for (uint32_t seed = 1; seed <= 30; ++seed) {
    VoxelGrid g = RandomSolidGrid(12, 0.3, seed);
    const VoxelTopology before = ComputeVoxelTopology(g);
    BridgeDiagonalContacts(g);
    const VoxelTopology after = ComputeVoxelTopology(g);
    ASSERT_EQ(after.shells, before.shells) << seed;
    ASSERT_EQ(after.genus, before.genus) << seed;
  }
}

// The search runs on the threads until a scan's first bridge: random solids with many
// contacts get the same bridges, counts and grid on 1 and 3 threads.
TEST(DiagonalBridging, TheSameBridgesOnAnyThreadCount) {
  int bridged = 0;
  for (uint32_t seed = 1; seed <= 10; ++seed) {
    VoxelGrid one = RandomSolidGrid(24, 0.3, seed), three = RandomSolidGrid(24, 0.3, seed);
    const BridgingResult a = BridgeDiagonalContacts(one, 3, 1);
    const BridgingResult b = BridgeDiagonalContacts(three, 3, 3);
    EXPECT_EQ(b.added, a.added) << seed;
    EXPECT_EQ(b.remaining, a.remaining) << seed;
    EXPECT_TRUE(one.states() == three.states()) << seed;
    bridged += a.added > 0;
    // A count alone (no scan bridges: max_scans 0) is the same too.
    VoxelGrid c1 = RandomSolidGrid(24, 0.3, seed), c3 = RandomSolidGrid(24, 0.3, seed);
    EXPECT_EQ(BridgeDiagonalContacts(c3, 0, 3).remaining,
              BridgeDiagonalContacts(c1, 0, 1).remaining);
  }
  EXPECT_GE(bridged, 5);
}

}  // namespace
}  // namespace membrane

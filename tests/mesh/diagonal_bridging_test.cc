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

}  // namespace
}  // namespace membrane

// The short-loop tunnel rule of the topology guard: a notch beside a one-voxel bridge is allowed
// to small plates, a hole through a wall is not.
#include "core/engine/tunnel_loop.h"

#include "core/engine/local_topology.h"
#include "core/engine/topology_guard.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

constexpr int kSize = 21;
constexpr int kMid = 10;

// An outside grid holding one soft boundary sheet in the plane z = kMid, x in [x_lo, x_hi],
// y in [3, 17].
VoxelGrid Sheet(int x_lo, int x_hi) {
  VoxelGrid g({kSize, kSize, kSize}, {0, 0, 0}, 1.0, OutsideState(1));
  for (int y = 3; y <= 17; ++y)
    for (int x = x_lo; x <= x_hi; ++x) g.set(Coord{x, y, kMid}, kBoundarySoft);
  return g;
}

// A wide sheet: its two sides meet only around its rim, 7 or more voxels away.
TEST(TunnelLoop, HoleInTheMiddleOfAWideSheetClosesALongLoop) {
  const VoxelGrid g = Sheet(3, 17);
  const int64_t v = g.Index(kMid, kMid, kMid);
  ASSERT_EQ(CountT6(OutsideMask(g, v)), 2);
  EXPECT_FALSE(TunnelClosesShortLoop(g, v, OutsideMask(g, v), 6));
  EXPECT_TRUE(TunnelClosesShortLoop(g, v, OutsideMask(g, v), 40));
}

// Beside the sheet's edge the voxel at x = 5 leaves a bridge one voxel wide (x = 4): the two
// sides meet around it in 4 steps.
TEST(TunnelLoop, NotchBesideAOneVoxelBridgeClosesAShortLoop) {
  const VoxelGrid g = Sheet(4, 17);
  const int64_t v = g.Index(5, kMid, kMid);
  ASSERT_EQ(CountT6(OutsideMask(g, v)), 2);
  EXPECT_TRUE(TunnelClosesShortLoop(g, v, OutsideMask(g, v), 6));
  EXPECT_FALSE(TunnelClosesShortLoop(g, v, OutsideMask(g, v), 3));
}

// A voxel on the sheet's edge opens no tunnel at all.
TEST(TunnelLoop, NoTunnelIsNoShortLoop) {
  const VoxelGrid g = Sheet(4, 17);
  const int64_t v = g.Index(4, kMid, kMid);
  ASSERT_NE(CountT6(OutsideMask(g, v)), 2);
  EXPECT_FALSE(TunnelClosesShortLoop(g, v, OutsideMask(g, v), 40));
}

// The guard allows the notch from short_loop_min_plate on, never next to a hard voxel, and
// never when the rule is off.
TEST(TunnelLoop, GuardAllowsTheNotchFromItsPlateSizeAwayFromHardVoxels) {
  VoxelGrid g = Sheet(4, 17);
  const int64_t v = g.Index(5, kMid, kMid);
  GuardOptions o;  // tunnels from n = 5, short-loop tunnels from n = 3 within 6 steps
  o.plate_size = 3;
  EXPECT_TRUE(GuardAllowsRemoval(g, v, o));
  o.plate_size = 2;
  EXPECT_FALSE(GuardAllowsRemoval(g, v, o));
  o.plate_size = 3;
  o.short_loop_min_plate = 0;
  EXPECT_FALSE(GuardAllowsRemoval(g, v, o));
  o.short_loop_min_plate = 3;
  g.set(Coord{6, kMid, kMid}, kBoundaryHard);
  EXPECT_FALSE(GuardAllowsRemoval(g, v, o));
  // The wide sheet's middle is a hole through a wall: refused below the tunnel size.
  const VoxelGrid wide = Sheet(3, 17);
  EXPECT_FALSE(GuardAllowsRemoval(wide, wide.Index(kMid, kMid, kMid), o));
  o.plate_size = 5;
  EXPECT_TRUE(GuardAllowsRemoval(wide, wide.Index(kMid, kMid, kMid), o));
}

}  // namespace
}  // namespace membrane

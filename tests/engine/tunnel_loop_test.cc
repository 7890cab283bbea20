// The short-loop tunnel rules of the topology guard: a notch beside a one-voxel bridge is allowed
// to small plates (along a wall too, when one generation is on both sides), a hole through a
// wall is not.
#include "core/engine/tunnel_loop.h"

#include <algorithm>
#include <cstdlib>

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

// The guard allows the notch from short_loop_min_plate on, never beside hard voxels that are
// not in one face layer, and never when the rule is off.
TEST(TunnelLoop, GuardAllowsTheNotchFromItsPlateSizeAwayFromHardVoxels) {
  VoxelGrid g = Sheet(4, 17);
  const int64_t v = g.Index(5, kMid, kMid);
  GuardOptions o;  // tunnels from n = 5, short-loop tunnels from n = 3 within 6 steps
  o.plate_size = 3;
  EXPECT_TRUE(GuardAllowsRemoval(g, v, o));
  o.plate_size = 2;
  EXPECT_FALSE(GuardAllowsRemoval(g, v, o));
  o.plate_size = 3;
  o.sizes.short_loop_min_plate = 0;
  EXPECT_FALSE(GuardAllowsRemoval(g, v, o));
  o.sizes.short_loop_min_plate = 3;
  g.set(Coord{6, kMid, kMid}, kBoundaryHard);  // hard neighbours in two face layers
  g.set(Coord{5, kMid + 1, kMid}, kBoundaryHard);
  EXPECT_FALSE(GuardAllowsRemoval(g, v, o));
  // The wide sheet's middle is a hole through a wall: refused below the tunnel size.
  const VoxelGrid wide = Sheet(3, 17);
  EXPECT_FALSE(GuardAllowsRemoval(wide, wide.Index(kMid, kMid, kMid), o));
  o.plate_size = 5;
  EXPECT_TRUE(GuardAllowsRemoval(wide, wide.Index(kMid, kMid, kMid), o));
}

// Below the object's tunnel plate a tunnel away from hard voxels needs data around it: the
// hole in the middle of the wide sheet (a long loop) is refused to a plate of 5 with no hard
// voxel near, allowed once the sheet within 5 voxels, outside the tunnel's own block, is hard
// (112 hard voxels, 2 * 5^2 needed), and refused again when only every third of them is.
// A plate of the object's size needs none.
TEST(TunnelLoop, ATunnelSmallForTheObjectNeedsDataAroundIt) {
  VoxelGrid g = Sheet(3, 17);
  const int64_t v = g.Index(kMid, kMid, kMid);
  GuardOptions o;
  o.plate_size = 5;
  EXPECT_TRUE(GuardAllowsRemoval(g, v, o));
  o.sizes.object_tunnel_plate = 6;
  EXPECT_FALSE(GuardAllowsRemoval(g, v, o));
  auto paint = [&g](int every) {
    for (int y = 3; y <= 17; ++y)
      for (int x = 3; x <= 17; ++x) {
        const bool near = std::max(std::abs(x - kMid), std::abs(y - kMid)) <= 1;
        const bool hard = !near && (x + y) % every == 0;
        g.set(Coord{x, y, kMid}, hard ? kBoundaryHard : kBoundarySoft);
      }
  };
  paint(1);
  EXPECT_TRUE(GuardAllowsRemoval(g, v, o));
  paint(3);
  EXPECT_FALSE(GuardAllowsRemoval(g, v, o));
  o.plate_size = 6;
  EXPECT_TRUE(GuardAllowsRemoval(g, v, o));
}

TEST(TunnelLoop, InOneFaceLayer) {
  auto bit = [](int dx, int dy, int dz) { return 1u << NeighbourBit(dx, dy, dz); };
  EXPECT_TRUE(InOneFaceLayer(0));
  EXPECT_TRUE(InOneFaceLayer(bit(1, -1, 0) | bit(1, 1, 1) | bit(1, 0, -1)));
  EXPECT_TRUE(InOneFaceLayer(bit(-1, -1, -1) | bit(1, -1, 1)));  // both in y = -1
  EXPECT_FALSE(InOneFaceLayer(bit(1, 0, 0) | bit(-1, 0, 0)));    // two sides of a gap
  EXPECT_TRUE(InOneFaceLayer(bit(0, 0, 1) | bit(1, 1, 1)));      // z = +1
  EXPECT_FALSE(InOneFaceLayer(bit(0, 0, 1) | bit(1, 1, -1)));
}

// Beside a hard wall (in the face layer y = +1 of the notch voxel), the notch is allowed from
// wall_notch_min_plate on when both sides carry one generation; not when the generations
// differ, nor between hard voxels on two sides (a gap in a wall).
TEST(TunnelLoop, GuardAllowsANotchAlongAWallWhenOneGenerationIsOnBothSides) {
  VoxelGrid g = Sheet(4, 17);
  for (int x = 4; x <= 6; ++x) g.set(Coord{x, kMid + 1, kMid}, kBoundaryHard);
  const int64_t v = g.Index(5, kMid, kMid);
  GuardOptions o;
  o.plate_size = 2;
  EXPECT_TRUE(SameGenerationAcrossTunnel(g, v, OutsideMask(g, v)));
  EXPECT_TRUE(GuardAllowsRemoval(g, v, o));
  o.sizes.wall_notch_min_plate = 3;
  EXPECT_FALSE(GuardAllowsRemoval(g, v, o));
  o.sizes.wall_notch_min_plate = 0;
  EXPECT_FALSE(GuardAllowsRemoval(g, v, o));
  o.sizes.wall_notch_min_plate = 2;
  g.set(Coord{5, kMid, kMid - 1}, OutsideState(2));
  EXPECT_FALSE(SameGenerationAcrossTunnel(g, v, OutsideMask(g, v)));
  EXPECT_FALSE(GuardAllowsRemoval(g, v, o));
  g.set(Coord{5, kMid, kMid - 1}, OutsideState(1));
  g.set(Coord{4, kMid - 1, kMid}, kBoundaryHard);  // now hard on both sides in y
  EXPECT_FALSE(GuardAllowsRemoval(g, v, o));
}

// The handle retry's strict sizes open wall notches only from n = 5: with classify_strict, a
// notch the guard allows at n = 2, 3 or 4 is told apart as loose, and one the strict sizes
// allow is not.
TEST(TunnelLoop, ANotchTheStrictSizesRefuseIsLoose) {
  VoxelGrid g = Sheet(4, 17);
  for (int x = 4; x <= 6; ++x) g.set(Coord{x, kMid + 1, kMid}, kBoundaryHard);
  const int64_t v = g.Index(5, kMid, kMid);
  GuardOptions o;
  o.plate_size = 2;
  EXPECT_EQ(ClassifyRemoval(g, v, o), GuardVerdict::kAllowed);
  o.classify_strict = true;
  EXPECT_EQ(o.strict.wall_notch_min_plate, 5);
  EXPECT_EQ(ClassifyRemoval(g, v, o), GuardVerdict::kAllowedLoosely);
  o.plate_size = 3;
  EXPECT_EQ(ClassifyRemoval(g, v, o), GuardVerdict::kAllowedLoosely);
  o.plate_size = 4;
  EXPECT_EQ(ClassifyRemoval(g, v, o), GuardVerdict::kAllowedLoosely);
  o.plate_size = 2;
  o.strict.wall_notch_min_plate = 2;
  EXPECT_EQ(ClassifyRemoval(g, v, o), GuardVerdict::kAllowed);
  o.strict.wall_notch_min_plate = 0;
  EXPECT_EQ(ClassifyRemoval(g, v, o), GuardVerdict::kAllowedLoosely);
}

}  // namespace
}  // namespace membrane

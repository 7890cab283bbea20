#include "core/engine/incursion_test.h"

#include <vector>

#include "core/engine/hard_voxel_points.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

// A 7^3 grid, all inside soft, with outside voxels placed by each test.
VoxelGrid SmallGrid() { return VoxelGrid({7, 7, 7}, {0, 0, 0}, 1.0, kInsideSoft); }

// Figure 8(b): outside voxels of different generations on opposite faces of a hard voxel,
// not joined around it: the plate got through the wall.
TEST(IncursionTest, DifferentGenerationsOnOppositeFacesFire) {
  VoxelGrid g = SmallGrid();
  g.set(Coord{3, 3, 3}, kBoundaryHard);
  g.set(Coord{2, 3, 3}, OutsideState(1));
  g.set(Coord{4, 3, 3}, OutsideState(2));
  EXPECT_TRUE(PaperIncursion(g, g.Index(3, 3, 3)));
}

// Property 6 / Figure 8(a): same generation on both sides is no incursion.
TEST(IncursionTest, Property6SameGenerationOnBothSidesDoesNotFire) {
  VoxelGrid g = SmallGrid();
  g.set(Coord{3, 3, 3}, kBoundaryHard);
  g.set(Coord{2, 3, 3}, OutsideState(2));
  g.set(Coord{4, 3, 3}, OutsideState(2));
  EXPECT_FALSE(PaperIncursion(g, g.Index(3, 3, 3)));
}

// Property 5: a one-voxel protuberance has its two sides local-arc connected around its tip.
TEST(IncursionTest, Property5LocalArcConnectedSidesDoNotFire) {
  VoxelGrid g = SmallGrid();
  g.set(Coord{3, 3, 3}, kBoundaryHard);
  g.set(Coord{2, 3, 3}, OutsideState(1));
  g.set(Coord{4, 3, 3}, OutsideState(2));
  // Path 2,3,3 -> 2,3,4 -> 3,3,4 -> 4,3,4 -> 4,3,3 of outside voxels over the tip.
  g.set(Coord{2, 3, 4}, OutsideState(1));
  g.set(Coord{3, 3, 4}, OutsideState(1));
  g.set(Coord{4, 3, 4}, OutsideState(2));
  EXPECT_FALSE(PaperIncursion(g, g.Index(3, 3, 3)));
}

TEST(IncursionTest, ThickWallOfTwoHardVoxelsFires) {
  VoxelGrid g = SmallGrid();
  g.set(Coord{3, 3, 3}, kBoundaryHard);
  g.set(Coord{4, 3, 3}, kBoundaryHard);
  g.set(Coord{2, 3, 3}, OutsideState(1));
  g.set(Coord{5, 3, 3}, OutsideState(2));
  EXPECT_FALSE(PaperIncursion(g, g.Index(3, 3, 3)));
  EXPECT_TRUE(ThickWallIncursion(g, g.Index(3, 3, 3), 3, ThinPartRule{.detour = 0}));
  EXPECT_FALSE(ThickWallIncursion(g, g.Index(3, 3, 3), 1, ThinPartRule{.detour = 0}));
}

// A thin part two hard voxels thick, (6, 6, 6) and (7, 6, 6), whose sides are joined through
// the outside two voxels away from it (outside the 3-wide box): 5,6,6 -> 5,7,6 -> 5,8,6 -> ...
// -> 8,8,6 -> 8,7,6 -> 8,6,6; 6,7,6 and 7,7,6 stay inside.
VoxelGrid JoinedAroundRun() {
  VoxelGrid g({13, 13, 13}, {0, 0, 0}, 1.0, kInsideSoft);
  g.set(Coord{6, 6, 6}, kBoundaryHard);
  g.set(Coord{7, 6, 6}, kBoundaryHard);
  g.set(Coord{5, 6, 6}, OutsideState(1));
  g.set(Coord{8, 6, 6}, OutsideState(2));
  for (int x = 5; x <= 8; ++x) g.set(Coord{x, 8, 6}, OutsideState(1));
  g.set(Coord{5, 7, 6}, OutsideState(1));
  g.set(Coord{8, 7, 6}, OutsideState(2));
  return g;
}

// Without the detour, or with a cube too small to hold the path, it fires; with a detour of 4
// (and no data test) it does not: a leg, not a wall with a dig behind it.
TEST(IncursionTest, ThickWallJoinedAroundWithinTheDetourDoesNotFire) {
  const VoxelGrid g = JoinedAroundRun();
  const int64_t v = g.Index(6, 6, 6);
  EXPECT_TRUE(ThickWallIncursion(g, v, 3, ThinPartRule{.detour = 0}));
  EXPECT_TRUE(ThickWallIncursion(g, v, 3, ThinPartRule{.detour = 1}));
  EXPECT_FALSE(ThickWallIncursion(g, v, 3, ThinPartRule{.detour = 4}));
  EXPECT_FALSE(IncursionAt(g, v, 3, ThinPartRule{.detour = 4}));
}

// Points on the planes x = x0 and x = x1 across the box of the run (y, z in [5, 8)).
std::vector<Point3f> PointsOnPlanes(float x0, float x1) {
  std::vector<Point3f> points;
  for (float x : {x0, x1})
    for (float y = 5.1f; y < 8; y += 0.2f)
      for (float z = 5.1f; z < 8; z += 0.2f) points.push_back({x, y, z});
  return points;
}

// Data on both faces of the run (a leg 2 voxels thick): the thin-part exception holds.
TEST(IncursionTest, ThinPartWithDataOnBothSidesDoesNotFire) {
  const VoxelGrid g = JoinedAroundRun();
  const HardVoxelPoints index(g, PointsOnPlanes(6.05f, 7.95f));
  const ThinPartRule rule{.detour = 4, .min_spread = 0.4, .points = &index};
  EXPECT_FALSE(ThickWallIncursion(g, g.Index(6, 6, 6), 3, rule));
  EXPECT_FALSE(IncursionAt(g, g.Index(7, 6, 6), 3, rule));
}

// A wall of one voxel, x = 6 in the 13^3 grid (a cup's bottom at twice its wall's voxel), with
// outside of two generations on its two sides, not joined around it: the paper's test fires.
// With data on both of its faces (x = 6.05 and 6.95, FacingGap 0.9) and the faces' gap read,
// it is a thin part; one scanned surface seen from both sides (x = 6.5) still fires.
TEST(IncursionTest, AOneVoxelWallWithDataOnBothFacesIsAThinPart) {
  VoxelGrid g({13, 13, 13}, {0, 0, 0}, 1.0, kInsideSoft);
  g.set(Coord{6, 6, 6}, kBoundaryHard);
  g.set(Coord{5, 6, 6}, OutsideState(1));
  g.set(Coord{7, 6, 6}, OutsideState(2));
  const int64_t v = g.Index(6, 6, 6);
  const HardVoxelPoints two_faces(g, PointsOnPlanes(6.05f, 6.95f));
  const HardVoxelPoints one_sheet(g, PointsOnPlanes(6.5f, 6.5f));
  EXPECT_TRUE(PaperIncursion(g, v));
  EXPECT_TRUE(PaperIncursion(g, v, ThinPartRule{.points = &two_faces}));  // the gap not read
  const ThinPartRule faces{.points = &two_faces, .min_face_gap = 0.6};
  EXPECT_FALSE(PaperIncursion(g, v, faces));
  EXPECT_FALSE(IncursionAt(g, v, 3, faces));
  EXPECT_TRUE(PaperIncursion(g, v, ThinPartRule{.points = &one_sheet, .min_face_gap = 0.6}));
  // A wall 0.9 voxel thick is no thin part for a gap of 1.
  EXPECT_TRUE(PaperIncursion(g, v, ThinPartRule{.points = &two_faces, .min_face_gap = 1.0}));
}

// Data on one surface only (a scanned wall at a data hole's rim, joined around the rim): the
// test fires, and so it does without points to read.
TEST(IncursionTest, JoinedAroundWithDataOnOneSideFires) {
  const VoxelGrid g = JoinedAroundRun();
  const HardVoxelPoints index(g, PointsOnPlanes(6.9f, 7.05f));
  EXPECT_TRUE(ThickWallIncursion(g, g.Index(6, 6, 6), 3,
                                 ThinPartRule{.detour = 4, .min_spread = 0.4, .points = &index}));
  EXPECT_TRUE(ThickWallIncursion(g, g.Index(6, 6, 6), 3,
                                 ThinPartRule{.detour = 4, .min_spread = 0.4, .points = nullptr}));
}

// The same wall with no outside path around it within the cube: a dig behind a wall fires.
TEST(IncursionTest, ThickWallNotJoinedWithinTheDetourFires) {
  VoxelGrid g({13, 13, 13}, {0, 0, 0}, 1.0, kInsideSoft);
  g.set(Coord{6, 6, 6}, kBoundaryHard);
  g.set(Coord{7, 6, 6}, kBoundaryHard);
  g.set(Coord{5, 6, 6}, OutsideState(1));
  g.set(Coord{8, 6, 6}, OutsideState(2));
  for (int x = 5; x <= 8; ++x) g.set(Coord{x, 11, 6}, OutsideState(1));  // 5 voxels away
  EXPECT_TRUE(ThickWallIncursion(g, g.Index(6, 6, 6), 3, ThinPartRule{.detour = 4}));
}

TEST(IncursionTest, ThickWallWithAnOutsidePathAroundDoesNotFire) {
  VoxelGrid g = SmallGrid();
  g.set(Coord{3, 3, 3}, kBoundaryHard);
  g.set(Coord{4, 3, 3}, kBoundaryHard);
  for (int x = 2; x <= 5; ++x) g.set(Coord{x, 4, 3}, OutsideState(1));
  g.set(Coord{2, 3, 3}, OutsideState(1));
  g.set(Coord{5, 3, 3}, OutsideState(2));
  EXPECT_FALSE(ThickWallIncursion(g, g.Index(3, 3, 3), 3, ThinPartRule{.detour = 0}));
}

TEST(IncursionTest, FrozenVoxelsActAsHard) {
  VoxelGrid g = SmallGrid();
  g.set(Coord{3, 3, 3}, kBoundaryFrozen);
  g.set(Coord{3, 2, 3}, OutsideState(1));
  g.set(Coord{3, 4, 3}, OutsideState(3));
  EXPECT_TRUE(IncursionAt(g, g.Index(3, 3, 3), 3, ThinPartRule{.detour = 4}));
}

}  // namespace
}  // namespace membrane

#include "core/engine/thin_wall_faces.h"

#include <cmath>
#include <cstdint>
#include <vector>

#include "gtest/gtest.h"

namespace membrane {
namespace {

// A 24^3 grid of unit voxels from the origin.
VoxelGrid UnitGrid() { return VoxelGrid({24, 24, 24}, {0, 0, 0}, 1.0, kInsideSoft); }

// The unit normal of the walls below: 30 degrees off x in the xy plane, so that a run along x
// crosses them obliquely (as the runs along x cross a cup's curved side).
constexpr double kNx = 0.8660254037844386, kNy = 0.5;

// Points on the plane n . p = offset (n = (kNx, kNy, 0)), a lattice of step 0.4 along the plane
// jittered by up to `jitter` voxels (deterministic) along each axis, within the grid's middle.
void AddSheet(double offset, double jitter, std::vector<Point3f>& points) {
  uint32_t state = 12345;
  auto next = [&] {
    state = state * 1664525u + 1013904223u;
    return (static_cast<double>(state >> 8) / (1 << 24)) * 2 - 1;
  };
  for (double t = -8; t <= 8; t += 0.4)
    for (double z = 6; z <= 18; z += 0.4) {
      const double x = 12 + offset * kNx - t * kNy, y = 12 + offset * kNy + t * kNx;
      points.push_back({static_cast<float>(x + jitter * next()),
                        static_cast<float>(y + jitter * next()),
                        static_cast<float>(z + jitter * next())});
    }
}

// The voxel of row (y, z) = (12, 12) whose centre lies about `offset` along the normal from the
// walls' origin (12, 12, 12): its centre (x + 0.5, 12.5, 12.5) lies (x + 0.5 - 12) kNx +
// 0.5 kNy along it.
Coord RowVoxel(double offset) {
  return Coord{static_cast<int>(std::lround(12 + (offset - 0.5 * kNy) / kNx - 0.5)), 12, 12};
}

// A wall 1.5 voxels thick, its two faces sampled, crossed along x (2.3 voxels between its faces
// along the run): each end faces its own face, and the gap is the wall's thickness.
TEST(FacingGapTest, TheTwoFacesOfAnObliqueThinWall) {
  std::vector<Point3f> points;
  AddSheet(0.0, 0.05, points);
  AddSheet(1.5, 0.05, points);
  const VoxelGrid g = UnitGrid();
  const HardVoxelPoints index(g, points);
  const double gap = FacingGap(g, index, RowVoxel(-1.2), RowVoxel(2.7));
  EXPECT_GT(gap, 1.1);
  EXPECT_LT(gap, 1.9);
  // Either way round.
  EXPECT_NEAR(FacingGap(g, index, RowVoxel(2.7), RowVoxel(-1.2)), gap, 1e-9);
}

// One noisy surface (0.15 voxel, as a scan's) seen from both of its sides, as a dig behind a
// scanned wall sees it: both ends face the one sheet.
TEST(FacingGapTest, OneNoisySurfaceSeenFromBothSides) {
  std::vector<Point3f> points;
  AddSheet(0.0, 0.15, points);
  const VoxelGrid g = UnitGrid();
  const HardVoxelPoints index(g, points);
  EXPECT_LT(FacingGap(g, index, RowVoxel(-1.3), RowVoxel(1.3)), 0.4);
}

// No point near an end: no reading. Both ends on one side of one surface face it alike.
TEST(FacingGapTest, NoWallBetweenTheEnds) {
  std::vector<Point3f> points;
  AddSheet(0.0, 0.05, points);
  const VoxelGrid g = UnitGrid();
  const HardVoxelPoints index(g, points);
  EXPECT_EQ(FacingGap(g, index, RowVoxel(-1.3), Coord{2, 2, 2}), -1);
  EXPECT_LT(FacingGap(g, index, RowVoxel(-1.3), RowVoxel(-2.3)), 0.2);
}

}  // namespace
}  // namespace membrane

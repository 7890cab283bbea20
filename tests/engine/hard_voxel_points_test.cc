#include "core/engine/hard_voxel_points.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <vector>

#include "gtest/gtest.h"

namespace membrane {
namespace {

// A 10^3 grid of unit voxels from the origin: voxel (x, y, z) covers [x, x + 1) and so on.
VoxelGrid UnitGrid() { return VoxelGrid({10, 10, 10}, {0, 0, 0}, 1.0, kInsideSoft); }

// Points on the plane x = x0, on a lattice of step 0.25 over y, z in [3, 6).
void AddPlane(float x0, std::vector<Point3f>& points) {
  for (float y = 3.125f; y < 6; y += 0.25f)
    for (float z = 3.125f; z < 6; z += 0.25f) points.push_back({x0, y, z});
}

TEST(HardVoxelPointsTest, OneSurfaceLiesOnItsPlane) {
  std::vector<Point3f> points;
  AddPlane(4.5f, points);
  const VoxelGrid g = UnitGrid();
  const HardVoxelPoints index(g, points);
  EXPECT_EQ(index.points(), static_cast<int64_t>(points.size()));
  EXPECT_NEAR(index.PlaneSpread(g, Coord{3, 3, 3}, Coord{5, 5, 5}), 0.0, 1e-3);
}

// Two surfaces 1 voxel apart (the faces of a part 1 voxel thick): half their distance (less
// than the 0.87 voxels the points spread along each surface in a box 3 voxels wide).
TEST(HardVoxelPointsTest, TwoFacingSurfacesSpreadByHalfTheirDistance) {
  std::vector<Point3f> points;
  AddPlane(4.0f, points);
  AddPlane(5.0f, points);
  const VoxelGrid g = UnitGrid();
  const HardVoxelPoints index(g, points);
  EXPECT_NEAR(index.PlaneSpread(g, Coord{3, 3, 3}, Coord{5, 5, 5}), 0.5, 1e-3);
  // A box holding one of them only sees one surface.
  EXPECT_NEAR(index.PlaneSpread(g, Coord{3, 3, 3}, Coord{4, 5, 5}), 0.0, 1e-3);
}

TEST(HardVoxelPointsTest, TooFewPointsAreNoEvidence) {
  const std::vector<Point3f> points = {{4.5f, 4.5f, 4.5f}, {4.2f, 4.7f, 4.1f}, {4.9f, 4.1f, 4.4f}};
  const VoxelGrid g = UnitGrid();
  const HardVoxelPoints index(g, points);
  EXPECT_EQ(index.PlaneSpread(g, Coord{3, 3, 3}, Coord{5, 5, 5}), -1);
  // Three points lie on their plane.
  EXPECT_NEAR(index.PlaneSpread(g, Coord{3, 3, 3}, Coord{5, 5, 5}, 3), 0.0, 1e-3);
  // A box past the array holds nothing.
  EXPECT_EQ(index.PlaneSpread(g, Coord{12, 0, 0}, Coord{14, 2, 2}, 1), -1);
}

// The plane's normal, whichever way it points; none without enough points.
TEST(HardVoxelPointsTest, PlaneNormalIsAcrossThePlane) {
  std::vector<Point3f> points;
  AddPlane(4.5f, points);
  const VoxelGrid g = UnitGrid();
  const HardVoxelPoints index(g, points);
  std::array<double, 3> n{};
  ASSERT_TRUE(index.PlaneNormal(g, Coord{3, 3, 3}, Coord{5, 5, 5}, n));
  EXPECT_NEAR(std::abs(n[0]), 1.0, 1e-6);
  EXPECT_NEAR(n[1], 0.0, 1e-6);
  EXPECT_NEAR(n[2], 0.0, 1e-6);
  EXPECT_FALSE(index.PlaneNormal(g, Coord{7, 7, 7}, Coord{9, 9, 9}, n));
}

TEST(HardVoxelPointsTest, NearestDistanceFromAVoxelCentre) {
  const std::vector<Point3f> points = {{4.5f, 4.5f, 6.0f}};
  const VoxelGrid g = UnitGrid();
  const HardVoxelPoints index(g, points);
  // Voxel (4, 4, 4)'s centre is (4.5, 4.5, 4.5): 1.5 from the point, which lies in voxel z 6.
  EXPECT_NEAR(index.NearestDistance(g, Coord{4, 4, 4}, 2), 1.5, 1e-6);
  // Outside the searched voxels: radius + 1.
  EXPECT_EQ(index.NearestDistance(g, Coord{4, 4, 4}, 1), 2.0);
  EXPECT_EQ(index.NearestDistance(g, Coord{0, 0, 0}, 1), 2.0);
}

TEST(HardVoxelPointsTest, SpotDistancesFromASubdividedVoxel) {
  const std::vector<Point3f> points = {{4.5f, 4.5f, 6.0f}};
  const VoxelGrid g = UnitGrid();
  const HardVoxelPoints index(g, points);
  std::vector<double> d;
  // One spot: the centre, as NearestDistance.
  index.SpotDistances(g, Coord{4, 4, 4}, 2, 1, d);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_NEAR(d[0], 1.5, 1e-6);
  // Two spots a side, x fastest: z 4.25 (the first four) and 4.75 (the last four); the spot
  // (4.25, 4.25, 4.25) lies sqrt(0.0625 + 0.0625 + 3.0625) from the point.
  index.SpotDistances(g, Coord{4, 4, 4}, 2, 2, d);
  ASSERT_EQ(d.size(), 8u);
  EXPECT_NEAR(d[0], std::sqrt(0.0625 + 0.0625 + 1.75 * 1.75), 1e-6);
  EXPECT_NEAR(d[7], std::sqrt(0.0625 + 0.0625 + 1.25 * 1.25), 1e-6);
  // Outside the searched voxels: radius + 1 for every spot.
  index.SpotDistances(g, Coord{4, 4, 4}, 1, 3, d);
  ASSERT_EQ(d.size(), 27u);
  for (double x : d) EXPECT_EQ(x, 2.0);
}

// Sorted on two threads (enough points for the sort to split), the index is the one thread's:
// the same voxels, and the same points in the same order (the same sums, bit for bit).
TEST(HardVoxelPointsTest, TheSameIndexOnAnyThreadCount) {
  const VoxelGrid g({40, 40, 40}, {0, 0, 0}, 1.0, kInsideSoft);
  std::vector<Point3f> points;
  uint64_t state = 12345;
  auto next = [&] {  // a fixed linear congruential sequence in [2, 38)
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return 2.0f + 36.0f * static_cast<float>(state >> 40) / static_cast<float>(1 << 24);
  };
  for (int i = 0; i < 200000; ++i) points.push_back({next(), next(), next()});
  const HardVoxelPoints one(g, points, 1);
  for (int threads : {2, 3}) {
    const HardVoxelPoints many(g, points, threads);
    ASSERT_EQ(many.points(), one.points());
    ASSERT_TRUE(std::equal(many.voxels().begin(), many.voxels().end(), one.voxels().begin(),
                           one.voxels().end()));
    for (int c = 4; c < 36; c += 5) {
      const Coord lo{c - 1, c - 2, c - 1}, hi{c + 1, c + 1, c + 2};
      EXPECT_EQ(many.PlaneSpread(g, lo, hi), one.PlaneSpread(g, lo, hi)) << c;
      const Coord at{c, c, c};
      EXPECT_EQ(many.NearestDistance(g, at, 2), one.NearestDistance(g, at, 2)) << c;
    }
  }
}

}  // namespace
}  // namespace membrane

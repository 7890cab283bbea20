// Opening plugged holes: a slab pierced by a hole whose waist a plug closes gets its hole back
// (one handle more); a wall whose scanner missed a disc (data around it, facing along the
// passage) keeps its plug; without the points nothing is opened.
#include "core/engine/hole_opening.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numeric>
#include <vector>

#include "core/engine/hard_voxel_points.h"
#include "core/engine/membrane_invariants.h"
#include "core/engine/voxel_topology.h"
#include "tests/engine/final_membrane_states.h"

namespace membrane {
namespace {

constexpr int kDim = 40;
constexpr double kCx = 20.0, kCy = 20.0;  // the hole's axis (along z)
constexpr double kRadius = 3.0;           // the hole's radius, voxels

double FromAxis(double x, double y) { return std::hypot(x - kCx, y - kCy); }

// A membrane as the shrink leaves it: `solid(x, y, z)` (voxel coordinates) non-outside, the rest
// outside; voxels holding points hard; a non-outside voxel beside the outside BOUNDARY, a soft
// one with an outside face neighbour FROZEN.
VoxelGrid Membrane(const std::function<bool(int, int, int)>& solid,
                   const std::vector<Point3f>& points) {
  VoxelGrid grid({kDim, kDim, kDim}, {0, 0, 0}, 1.0, OutsideState(1));
  for (int z = 1; z + 1 < kDim; ++z)
    for (int y = 1; y + 1 < kDim; ++y)
      for (int x = 1; x + 1 < kDim; ++x)
        if (solid(x, y, z)) grid.set(grid.Index(x, y, z), kInsideSoft);
  for (const Point3f& p : points) {
    const Coord c{static_cast<int>(p[0]), static_cast<int>(p[1]), static_cast<int>(p[2])};
    grid.set(c, kInsideHard);
  }
  SetFinalMembraneStates(grid);
  return grid;
}

// Points every 0.25 voxel on the slab x, y in [2, 38), z in [z0, z1): its two faces (the upper
// one only when `both_faces`), and the wall of the hole of kRadius around the axis (when
// `hole_wall`); the faces stop at the hole.
std::vector<Point3f> SlabPoints(double z0, double z1, bool hole_wall, bool both_faces = true) {
  std::vector<Point3f> points;
  for (double x = 2.125; x < 38; x += 0.25)
    for (double y = 2.125; y < 38; y += 0.25) {
      if (FromAxis(x, y) < kRadius) continue;
      points.push_back({static_cast<float>(x), static_cast<float>(y), static_cast<float>(z0)});
      if (both_faces)
        points.push_back({static_cast<float>(x), static_cast<float>(y), static_cast<float>(z1)});
    }
  if (hole_wall) {
    for (double z = z0 + 0.125; z < z1; z += 0.25)
      for (int k = 0; k < 128; ++k) {
        const double a = 2 * M_PI * k / 128;
        points.push_back({static_cast<float>(kCx + kRadius * std::cos(a)),
                          static_cast<float>(kCy + kRadius * std::sin(a)), static_cast<float>(z)});
      }
  }
  return points;
}

// The slab x, y in [2, 38), z in [10, 30), pierced along the axis except at its waist, z in
// [18, 22): the plug.
bool PluggedSlab(int x, int y, int z) {
  const bool slab = x >= 2 && x < 38 && y >= 2 && y < 38 && z >= 10 && z < 30;
  const bool hole = FromAxis(x + 0.5, y + 0.5) < kRadius && (z < 18 || z >= 22);
  return slab && !hole;
}

int Genus(const VoxelGrid& grid) {
  const VoxelTopology t = ComputeVoxelTopology(grid);
  return std::accumulate(t.genus.begin(), t.genus.end(), 0);
}

// A wall 2 voxels thick (z in [18, 20)) across the grid, the outside on both of its sides: a dig
// behind a scanned wall.
bool ThinWall(int x, int y, int z) {
  return x >= 2 && x < 38 && y >= 2 && y < 38 && z >= 18 && z < 20;
}

// Expects the hole opening with `options` to open nothing in `grid` and to leave it as it was.
void ExpectKeptClosed(VoxelGrid& grid, const HardVoxelPoints& index,
                      const HoleOpeningOptions& options) {
  const VoxelStates before = grid.states();
  absl::StatusOr<HoleOpeningStats> stats =
      OpenPluggedHoles(grid, options, &index, CancelToken::Never());
  ASSERT_TRUE(stats.ok()) << stats.status();
  EXPECT_EQ(stats->opened, 0);
  EXPECT_EQ(grid.states(), before);
}

// The search for plugs runs on the threads until the first carve, and the scan after it goes on
// from there: the same carves, statistics and grid on 1 and 3 threads.
TEST(HoleOpeningTest, OpensTheSamePlugsOnAnyThreadCount) {
  const std::vector<Point3f> points = SlabPoints(10, 30, /*hole_wall=*/true);
  VoxelGrid one = Membrane(PluggedSlab, points), three = Membrane(PluggedSlab, points);
  const HardVoxelPoints index(one, points);
  absl::StatusOr<HoleOpeningStats> a =
      OpenPluggedHoles(one, HoleOpeningOptions(), &index, CancelToken::Never(), 1);
  absl::StatusOr<HoleOpeningStats> b =
      OpenPluggedHoles(three, HoleOpeningOptions(), &index, CancelToken::Never(), 3);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->opened, 1);
  EXPECT_EQ(b->opened, a->opened);
  EXPECT_EQ(b->refused, a->refused);
  EXPECT_EQ(b->wall_cores, a->wall_cores);
  EXPECT_EQ(b->carved_voxels, a->carved_voxels);
  EXPECT_TRUE(one.states() == three.states());
}

// A slab 20 voxels thick pierced by a hole 6 voxels wide, closed at its waist by a plug 4 voxels
// thick (soft: no data inside the hole): the hole's wall is data all around, facing the plug.
TEST(HoleOpeningTest, OpensAPlugRimmedByTheHolesWall) {
  const std::vector<Point3f> points = SlabPoints(10, 30, /*hole_wall=*/true);
  VoxelGrid grid = Membrane(PluggedSlab, points);
  const HardVoxelPoints index(grid, points);
  ASSERT_EQ(Genus(grid), 0);
  absl::StatusOr<HoleOpeningStats> stats =
      OpenPluggedHoles(grid, HoleOpeningOptions(), &index, CancelToken::Never());
  ASSERT_TRUE(stats.ok()) << stats.status();
  EXPECT_EQ(stats->opened, 1);
  EXPECT_EQ(stats->carved_voxels, 4);
  // The hole's rim is joined around the plug well inside the join test's cube: the carve was
  // counted there, not over the grid.
  EXPECT_EQ(stats->whole_grid_counts, 0);
  const VoxelTopology t = ComputeVoxelTopology(grid);
  EXPECT_EQ(t.shells, 1);
  EXPECT_EQ(t.cavities, 0);
  EXPECT_EQ(Genus(grid), 1);
  InvariantOptions io;
  io.require_property3 = true;
  EXPECT_TRUE(CheckMembraneInvariants(grid, io).ok()) << CheckMembraneInvariants(grid, io);

  // Options off, or no points: nothing opens.
  VoxelGrid again = Membrane(PluggedSlab, points);
  HoleOpeningOptions off;
  off.enabled = false;
  EXPECT_EQ(OpenPluggedHoles(again, off, &index, CancelToken::Never())->opened, 0);
  EXPECT_EQ(OpenPluggedHoles(again, HoleOpeningOptions(), nullptr, CancelToken::Never())->opened,
            0);
  EXPECT_EQ(Genus(again), 0);
}

// A thin wall scanned on one face, where the scanner missed a disc 6 voxels wide: the data
// around the gap are the wall's face, facing along the passage, so the gap is a data hole of
// one surface, not a hole through the object.
TEST(HoleOpeningTest, KeepsAWallsDataHoleClosed) {
  const std::vector<Point3f> points =
      SlabPoints(18, 19.99, /*hole_wall=*/false, /*both_faces=*/false);
  VoxelGrid grid = Membrane(ThinWall, points);
  const HardVoxelPoints index(grid, points);
  ExpectKeptClosed(grid, index, HoleOpeningOptions());
  // The facing of the data keeps it, and so does the wall-core test (the wall's face has the
  // outside right behind it); without both the plug is opened.
  HoleOpeningOptions any_facing;
  any_facing.max_facing_cos = 2;
  ExpectKeptClosed(grid, index, any_facing);
  any_facing.wall_core_depth = 0;
  EXPECT_EQ(OpenPluggedHoles(grid, any_facing, &index, CancelToken::Never())->opened, 1);
  EXPECT_EQ(Genus(grid), 1);
}

// A slab pierced by a funnel whose waist is 2.4 voxels wide, its axis off the voxel centres
// (at x = y = 20.2), plugged by the one voxel at the waist that no wall point lies in: the
// funnel's walls curve within a plane fit's 3x3x3 voxels and every voxel centre at the waist
// lies nearer than a voxel to them; the data lining the passage on both sides of the plug and a
// line through the plug's voxel 1.15 voxels from them (0.05 voxel off the axis) open it.
constexpr double kWaistAxis = 20.2;
constexpr double kWaistRadius = 1.2;

// The funnel's radius at height z: kWaistRadius at z = 20.5, widening both ways.
double FunnelRadius(double z) { return kWaistRadius + 0.15 * (z - 20.5) * (z - 20.5); }

double FromWaistAxis(double x, double y) { return std::hypot(x - kWaistAxis, y - kWaistAxis); }

// Points every 0.25 voxel on the slab's faces z = 14 and 26 (x, y in [2, 38), outside the
// funnel) and on the funnel's wall between them (or, `wall_only`, a wall 2 voxels thick at
// z = 19.99, scanned on one face, missing a disc of the waist's radius: no funnel).
std::vector<Point3f> FunnelPoints(bool wall_only) {
  std::vector<Point3f> points;
  const double z0 = wall_only ? 19.99 : 14, z1 = 26;
  for (double x = 2.125; x < 38; x += 0.25)
    for (double y = 2.125; y < 38; y += 0.25) {
      const double r = FromWaistAxis(x, y);
      if (r < (wall_only ? kWaistRadius : FunnelRadius(z0))) continue;
      points.push_back({static_cast<float>(x), static_cast<float>(y), static_cast<float>(z0)});
      if (!wall_only && r >= FunnelRadius(z1))
        points.push_back({static_cast<float>(x), static_cast<float>(y), static_cast<float>(z1)});
    }
  if (!wall_only) {
    for (double z = z0 + 0.0625; z < z1; z += 0.125) {
      const double r = FunnelRadius(z);
      const int n = static_cast<int>(2 * M_PI * r * 8);
      for (int k = 0; k < n; ++k) {
        const double a = 2 * M_PI * k / n;
        points.push_back({static_cast<float>(kWaistAxis + r * std::cos(a)),
                          static_cast<float>(kWaistAxis + r * std::sin(a)),
                          static_cast<float>(z)});
      }
    }
  }
  return points;
}

// The slab z in [14, 26) without the funnel's voxels (centre inside its radius), but for the
// waist layer z = 20: the plug.
bool PluggedFunnel(int x, int y, int z) {
  const bool slab = x >= 2 && x < 38 && y >= 2 && y < 38 && z >= 14 && z < 26;
  const bool hole = FromWaistAxis(x + 0.5, y + 0.5) < FunnelRadius(z + 0.5) && z != 20;
  return slab && !hole;
}

TEST(HoleOpeningTest, OpensAWaistNarrowerThanAPlaneFit) {
  const std::vector<Point3f> points = FunnelPoints(/*wall_only=*/false);
  VoxelGrid grid = Membrane(PluggedFunnel, points);
  const HardVoxelPoints index(grid, points);
  ASSERT_EQ(Genus(grid), 0);
  // Every voxel centre at the waist lies nearer than a voxel to the points: the centres alone
  // keep the plug closed.
  HoleOpeningOptions centres;
  centres.clearance_samples = 1;
  absl::StatusOr<HoleOpeningStats> stats =
      OpenPluggedHoles(grid, centres, &index, CancelToken::Never());
  ASSERT_TRUE(stats.ok()) << stats.status();
  EXPECT_EQ(stats->opened, 0);
  // Without the passage's data, neither the facing test nor the centres let it through.
  HoleOpeningOptions no_passage;
  no_passage.passage_sectors = 9;
  EXPECT_EQ(OpenPluggedHoles(grid, no_passage, &index, CancelToken::Never())->opened, 0);
  // Nor without the narrow waist: the rays meet the walls at the first step.
  HoleOpeningOptions not_narrow;
  not_narrow.narrow_steps = 0;
  EXPECT_EQ(OpenPluggedHoles(grid, not_narrow, &index, CancelToken::Never())->opened, 0);
  ASSERT_EQ(Genus(grid), 0);

  stats = OpenPluggedHoles(grid, HoleOpeningOptions(), &index, CancelToken::Never());
  ASSERT_TRUE(stats.ok()) << stats.status();
  EXPECT_EQ(stats->opened, 1);
  EXPECT_EQ(stats->carved_voxels, 1);
  const VoxelTopology t = ComputeVoxelTopology(grid);
  EXPECT_EQ(t.shells, 1);
  EXPECT_EQ(t.cavities, 0);
  EXPECT_EQ(Genus(grid), 1);
  InvariantOptions io;
  io.require_property3 = true;
  EXPECT_TRUE(CheckMembraneInvariants(grid, io).ok()) << CheckMembraneInvariants(grid, io);
}

// The same waist as a data hole in a wall scanned on one face: the data around it lie in one
// layer across the passage (none lines it), and face along it: it stays closed.
TEST(HoleOpeningTest, KeepsANarrowDataHoleInAWallClosed) {
  const std::vector<Point3f> points = FunnelPoints(/*wall_only=*/true);
  VoxelGrid grid = Membrane(ThinWall, points);
  const HardVoxelPoints index(grid, points);
  ExpectKeptClosed(grid, index, HoleOpeningOptions());
  // The facing of the data is what keeps it: without that test (and the wall-core test, which
  // this thin wall with outside on both sides also meets) the plug is opened.
  HoleOpeningOptions any_facing;
  any_facing.max_facing_cos = 2;
  any_facing.wall_core_depth = 0;
  EXPECT_EQ(OpenPluggedHoles(grid, any_facing, &index, CancelToken::Never())->opened, 1);
  EXPECT_EQ(Genus(grid), 1);
}

TEST(HoleOpeningTest, Cancels) {
  const std::vector<Point3f> points = SlabPoints(10, 30, /*hole_wall=*/true);
  VoxelGrid grid = Membrane([](int, int y, int) { return y >= 2; }, points);
  const HardVoxelPoints index(grid, points);
  CancelToken cancelled;
  cancelled.Cancel();
  EXPECT_EQ(OpenPluggedHoles(grid, HoleOpeningOptions(), &index, cancelled).status().code(),
            absl::StatusCode::kCancelled);
}

}  // namespace
}  // namespace membrane

#include "core/mesh/relaxation.h"

#include <cmath>

#include "core/engine/membrane_invariants.h"
#include "core/engine/voxel_topology.h"
#include "gtest/gtest.h"
#include "tests/mesh/test_grids.h"
#include "tests/support/cpu_time_cancel.h"

namespace membrane {
namespace {

using namespace membrane::testing;

// Boundary voxels frozen, as the engine leaves most of them (Property 3), with every fourth
// one hard, the data.
void FreezeWithSomeHard(VoxelGrid& g) {
  for (int64_t i = 0; i < g.size(); ++i) {
    if (!IsBoundary(g.at(i))) continue;
    g.set(i, i % 4 == 0 ? kBoundaryHard : kBoundaryFrozen);
  }
}

void ExpectSameTopology(const VoxelGrid& a, const VoxelGrid& b) {
  const VoxelTopology ta = ComputeVoxelTopology(a), tb = ComputeVoxelTopology(b);
  EXPECT_EQ(ta.shells, tb.shells);
  EXPECT_EQ(ta.genus, tb.genus);
  EXPECT_EQ(tb.cavities, 0);
}

void ExpectMembraneInvariants(const VoxelGrid& g) {
  InvariantOptions options;
  options.require_property3 = false;  // relaxation documents that Property 3 is given up
  const absl::Status s = CheckMembraneInvariants(g, options);
  EXPECT_TRUE(s.ok()) << s;
}

RelaxationStats RelaxOk(VoxelGrid& g) {
  const absl::StatusOr<RelaxationStats> stats = Relax(g, CancelToken::Never());
  EXPECT_TRUE(stats.ok()) << stats.status();
  return stats.ok() ? *stats : RelaxationStats{};
}

TEST(Relaxation, DlcOfAnIsolatedVoxelIs26) {
  VoxelGrid g = OutsideGrid(7);
  g.set(Coord{3, 3, 3}, kBoundaryFrozen);
  EXPECT_EQ(DiscreteLocalCurvature(g, Coord{3, 3, 3}), 26);
}

TEST(Relaxation, DlcOfAVoxelInAFlatFaceIsZeroWhenTheLayerBelowIsInside) {
  VoxelGrid g = OutsideGrid(12);
  MarkSolid(g, [](int x, int y, int z) {
    return x >= 2 && x < 10 && y >= 2 && y < 10 && z >= 2 && z < 7;
  });
  // (5, 5, 6) is on the top face: 9 outside above, 9 boundary around, 9 below of which the
  // centre column is inside.
  EXPECT_EQ(DiscreteLocalCurvature(g, Coord{5, 5, 6}), 9 - 9);
}

TEST(Relaxation, KeepsGenusOfTorus) {
  VoxelGrid g = SolidTorusGrid(40, 12, 4.5);
  FreezeWithSomeHard(g);
  const VoxelGrid before = g;
  const RelaxationStats stats = RelaxOk(g);
  EXPECT_GT(stats.phase1_moves + stats.phase2_moves, 0);
  ExpectSameTopology(before, g);
  EXPECT_EQ(ComputeVoxelTopology(g).genus, std::vector<int>{1});
  ExpectMembraneInvariants(g);
}

TEST(Relaxation, KeepsShellsOfTwoBalls) {
  VoxelGrid g = TwoBallsGrid(36, 7, 2);
  FreezeWithSomeHard(g);
  const VoxelGrid before = g;
  RelaxOk(g);
  ExpectSameTopology(before, g);
  EXPECT_EQ(ComputeVoxelTopology(g).shells, 2);
  ExpectMembraneInvariants(g);
}

TEST(Relaxation, NeverDeletesTwoSidedSheet) {
  // A square frame with a one-voxel membrane spanning its opening: outside on both sides of
  // the sheet (DLC about +16), so phase 2 wants it gone; removing it would open a handle.
  VoxelGrid g = OutsideGrid(24);
  MarkSolid(g, [](int x, int y, int z) {
    const bool frame = x >= 3 && x < 21 && y >= 3 && y < 21 && z >= 9 && z < 15 &&
                       !(x >= 8 && x < 16 && y >= 8 && y < 16);
    const bool sheet = x >= 8 && x < 16 && y >= 8 && y < 16 && z == 12;
    return frame || sheet;
  });
  FreezeWithSomeHard(g);
  const VoxelGrid before = g;
  RelaxOk(g);
  ExpectSameTopology(before, g);
  EXPECT_EQ(ComputeVoxelTopology(g).genus, std::vector<int>{0});
  int sheet_left = 0;
  for (int y = 9; y < 15; ++y)
    for (int x = 9; x < 15; ++x) sheet_left += !IsOutside(g.at(Coord{x, y, 12}));
  EXPECT_EQ(sheet_left, 36);
  ExpectMembraneInvariants(g);
}

TEST(Relaxation, NeverMovesHardVoxels) {
  VoxelGrid g = BallGrid(30, 10.5);
  FreezeWithSomeHard(g);
  const VoxelGrid before = g;
  RelaxOk(g);
  for (int64_t i = 0; i < g.size(); ++i) {
    if (!IsHard(before.at(i))) continue;
    ASSERT_FALSE(IsOutside(g.at(i))) << i;
    ASSERT_TRUE(IsHard(g.at(i))) << i;
    ASSERT_EQ(IsInside(before.at(i)), IsInside(g.at(i))) << i;  // hard boundary stays boundary
  }
}

TEST(Relaxation, FillsASoftDent) {
  // A flat face with a 3x3 pit one voxel deep: the pit's floor voxels see mostly inside
  // voxels around them (DLC far below -13) and fill it.
  VoxelGrid g = OutsideGrid(16);
  MarkSolid(
      g,
      [](int x, int y, int z) {
        const bool block = x >= 2 && x < 14 && y >= 2 && y < 14 && z >= 2 && z < 10;
        const bool pit = x >= 6 && x < 9 && y >= 6 && y < 9 && z >= 8;
        return block && !pit;
      },
      kBoundaryFrozen);
  const RelaxationStats stats = RelaxOk(g);
  EXPECT_GT(stats.phase1_moves, 0);
  EXPECT_GT(stats.phase1_added, 0);
  ExpectMembraneInvariants(g);
}

TEST(Relaxation, ShavesASoftBump) {
  VoxelGrid g = OutsideGrid(16);
  MarkSolid(
      g,
      [](int x, int y, int z) {
        const bool block = x >= 2 && x < 14 && y >= 2 && y < 14 && z >= 2 && z < 8;
        const bool bump = x == 7 && y == 7 && z == 8;
        return block || bump;
      },
      kBoundaryFrozen);
  const RelaxationStats stats = RelaxOk(g);
  EXPECT_GT(stats.phase2_moves, 0);
  EXPECT_TRUE(IsOutside(g.at(Coord{7, 7, 8})));
  ExpectMembraneInvariants(g);
}

TEST(Relaxation, NeverTouchesThePaddingLayers) {
  // A solid reaching the third layer: its dents next to the padding cannot fill outward.
  VoxelGrid g = OutsideGrid(14);
  MarkSolid(
      g,
      [](int x, int y, int z) {
        return x >= 2 && x < 12 && y >= 2 && y < 12 && z >= 2 && z < 12 &&
               !(x == 2 && y == 6 && z == 6);
      },
      kBoundaryFrozen);
  RelaxOk(g);
  const auto& d = g.dims();
  for (int z = 0; z < d[2]; ++z)
    for (int y = 0; y < d[1]; ++y)
      for (int x = 0; x < d[0]; ++x) {
        const bool padding =
            x < 2 || y < 2 || z < 2 || x >= d[0] - 2 || y >= d[1] - 2 || z >= d[2] - 2;
        if (padding) {
          ASSERT_TRUE(IsOutside(g.at(Coord{x, y, z}))) << x << " " << y << " " << z;
        }
      }
}

// A 96^3 block whose top has a 3x3 pit one voxel deep and a one-voxel bump every 12 voxels:
// moves in both phases, spread over many chunks and planes of the relaxation's passes.
VoxelGrid PittedBlockGrid() {
  VoxelGrid g = OutsideGrid(96);
  MarkSolid(
      g,
      [](int x, int y, int z) {
        const bool block = x >= 4 && x < 92 && y >= 4 && y < 92 && z >= 4 && z < 60;
        const bool pit = x % 12 >= 6 && x % 12 < 9 && y % 12 >= 6 && y % 12 < 9 && z >= 58;
        const bool bump = x % 12 == 2 && y % 12 == 2 && z == 60 && x > 4 && y > 4 && x < 91 &&
                          y < 91;
        return (block && !pit) || bump;
      },
      kBoundaryFrozen);
  return g;
}

// Phase 1's scan runs on the threads in z planes and phase 2's filter in chunks of 2^12
// boundary voxels: grids of several chunks relax to the same bytes and counts on 1, 2 and 3.
TEST(Relaxation, SameGridForAnyThreadCount) {
  std::vector<VoxelGrid> shapes;
  shapes.push_back(PittedBlockGrid());
  shapes.push_back(SolidTorusGrid(96, 30, 11.5));
  FreezeWithSomeHard(shapes.back());
  for (const VoxelGrid& shape : shapes) {
    int64_t boundary = 0;
    for (VoxelState v : shape.states()) boundary += IsBoundary(v) && !IsHard(v);
    ASSERT_GT(boundary, 3 * (int64_t{1} << 12));
    std::vector<VoxelGrid> relaxed;
    std::vector<RelaxationStats> stats;
    for (int threads : {1, 2, 3}) {
      VoxelGrid g = shape;
      RelaxationOptions options;
      options.threads = threads;
      const absl::StatusOr<RelaxationStats> s = Relax(g, CancelToken::Never(), options);
      ASSERT_TRUE(s.ok()) << s.status();
      relaxed.push_back(std::move(g));
      stats.push_back(*s);
    }
    EXPECT_GT(stats[0].phase1_moves + stats[0].phase2_moves, 0);
    for (int k = 1; k < 3; ++k) {
      EXPECT_TRUE(relaxed[k].states() == relaxed[0].states()) << "threads " << k + 1;
      EXPECT_EQ(stats[k].phase1_moves, stats[0].phase1_moves);
      EXPECT_EQ(stats[k].phase1_added, stats[0].phase1_added);
      EXPECT_EQ(stats[k].phase2_moves, stats[0].phase2_moves);
      EXPECT_EQ(stats[k].phase2_uncovered, stats[0].phase2_uncovered);
      EXPECT_EQ(stats[k].not_simple, stats[0].not_simple);
    }
  }
  VoxelGrid block = PittedBlockGrid();
  const RelaxationStats block_stats = RelaxOk(block);
  EXPECT_GE(block_stats.phase1_moves, 49);  // a move per pit at least
  EXPECT_GE(block_stats.phase2_moves, 49);  // and per bump
}

// Outside voxels carry their generation's label in their low bits, bit 0 among them: the DLC
// counts them by their outside bit alone. The pitted block with every outside voxel labelled 1
// (outside, bit 0 set) relaxes by the same moves to the same solid as with label 0.
TEST(Relaxation, OddOutsideLabelsCountAsOutside) {
  VoxelGrid even = PittedBlockGrid();
  VoxelGrid odd = even;
  for (int64_t i = 0; i < odd.size(); ++i)
    if (IsOutside(odd.at(i))) odd.set(i, OutsideState(1));
  ASSERT_EQ(DiscreteLocalCurvature(odd, Coord{7, 7, 58}),
            DiscreteLocalCurvature(even, Coord{7, 7, 58}));
  const RelaxationStats e = RelaxOk(even), o = RelaxOk(odd);
  EXPECT_GT(e.phase1_moves, 0);
  EXPECT_GT(e.phase2_moves, 0);
  EXPECT_EQ(o.phase1_moves, e.phase1_moves);
  EXPECT_EQ(o.phase1_added, e.phase1_added);
  EXPECT_EQ(o.phase2_moves, e.phase2_moves);
  EXPECT_EQ(o.phase2_uncovered, e.phase2_uncovered);
  for (int64_t i = 0; i < even.size(); ++i)
    ASSERT_EQ(IsOutside(odd.at(i)), IsOutside(even.at(i))) << i;
}

TEST(Relaxation, StopsWhenCancelledOnSeveralThreads) {
  VoxelGrid g = SolidTorusGrid(96, 30, 11.5);
  FreezeWithSomeHard(g);
  CancelToken cancel;
  cancel.Cancel();
  RelaxationOptions options;
  options.threads = 3;
  EXPECT_EQ(Relax(g, cancel, options).status().code(), absl::StatusCode::kCancelled);
  ExpectMembraneInvariants(g);
}

TEST(Relaxation, RejectsThresholdOutOfRange) {
  VoxelGrid g = BallGrid(12, 3.5);
  RelaxationOptions options;
  options.threshold = 27;
  EXPECT_EQ(Relax(g, CancelToken::Never(), options).status().code(), absl::StatusCode::kInvalidArgument);
}

TEST(Relaxation, StopsWhenCancelledAndLeavesAValidMembrane) {
  VoxelGrid g = SolidTorusGrid(40, 12, 4.5);
  FreezeWithSomeHard(g);
  CancelToken cancel;
  cancel.Cancel();
  const absl::StatusOr<RelaxationStats> stats = Relax(g, cancel);
  EXPECT_EQ(stats.status().code(), absl::StatusCode::kCancelled);
  ExpectMembraneInvariants(g);
}

// Latency in the thread's CPU time, so that a busy machine descheduling the test does not
// count as latency.
TEST(Relaxation, CancelReturnsWithin100Milliseconds) {
  VoxelGrid g = BallGrid(320, 150);
  FreezeWithSomeHard(g);
  // Cancel requested 2 ms of work in (the whole relaxation of this grid takes about 20 ms of
  // CPU: one scan of the grid, then the DLC of each boundary voxel summed when asked);
  // measured from the request, not from the first poll after it.
  CancelToken cancel;
  const CancelAfterThreadCpu canceller(cancel, 0.002);
  const absl::StatusOr<RelaxationStats> stats = Relax(g, cancel);
  const double latency = canceller.now() - canceller.cancelled_at();
  ASSERT_EQ(stats.status().code(), absl::StatusCode::kCancelled);
  EXPECT_LT(latency, 0.1);
}

}  // namespace
}  // namespace membrane

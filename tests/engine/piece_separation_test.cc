// Separating pieces of data joined by the shrink: two scanned boxes 5 voxels apart joined by a
// soft plug, and by an arch far from the data, come apart into two shells with a cut of one
// layer, and a handle of web far from the data is cut with them; their interiors, far from the
// data too, stay solid; a single piece is left alone, and so is a ball whose data miss a band
// around it (the cut would span its whole cross-section).
#include "core/engine/piece_separation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>

#include "core/engine/membrane_invariants.h"
#include "core/engine/voxel_topology.h"
#include "tests/engine/final_membrane_states.h"

namespace membrane {
namespace {

constexpr int kSide = 30;  // each box's side: its centre is 15 steps from its skin
constexpr int kGap = 5;    // voxels between the two boxes along x
constexpr int kAt = 4;     // each box's first voxel on y and z, the first box's on x
constexpr int kArch = 20;  // height of the arch's top over the boxes

using Predicate = std::function<bool(int, int, int)>;

bool InBox(int x, int y, int z, int x0) {
  return x >= x0 && x < x0 + kSide && y >= kAt && y < kAt + kSide && z >= kAt && z < kAt + kSide;
}

bool OnSkin(int x, int y, int z, int x0) {
  return InBox(x, y, z, x0) && std::min({x - x0, y - kAt, z - kAt, x0 + kSide - 1 - x,
                                         kAt + kSide - 1 - y, kAt + kSide - 1 - z}) == 0;
}

// Two boxes with hard skins and soft interiors, x in [kAt, kAt + kSide) and kGap voxels
// further; `joins(x, y, z)` (grid coordinates) adds soft voxels; the rest outside. States as
// the shrink leaves them.
VoxelGrid TwoBoxes(const Predicate& joins, bool second_box = true) {
  const int nx = 2 * kAt + 2 * kSide + kGap, ny = 2 * kAt + kSide, nz = 2 * kAt + kSide + kArch;
  VoxelGrid grid({nx, ny, nz}, {0, 0, 0}, 1.0, OutsideState(1));
  const int x1 = kAt + kSide + kGap;
  for (int z = 1; z + 1 < nz; ++z)
    for (int y = 1; y + 1 < ny; ++y)
      for (int x = 1; x + 1 < nx; ++x) {
        const bool box = InBox(x, y, z, kAt) || (second_box && InBox(x, y, z, x1));
        const bool skin = OnSkin(x, y, z, kAt) || (second_box && OnSkin(x, y, z, x1));
        if (skin) {
          grid.set(grid.Index(x, y, z), kInsideHard);
        } else if (box || joins(x, y, z)) {
          grid.set(grid.Index(x, y, z), kInsideSoft);
        }
      }
  SetFinalMembraneStates(grid);
  return grid;
}

// A plug 4 x 4 voxels across, filling the gap between the boxes' facing sides.
bool Plug(int x, int y, int z) {
  return x >= kAt + kSide && x < kAt + kSide + kGap && y >= 16 && y < 20 && z >= 16 && z < 20;
}

// An arch 2 x 2 voxels thick from the top of the first box up kArch voxels, across and down to
// the top of the second: its top is farther than 12 steps from either box.
bool Arch(int x, int y, int z) {
  const int top = kAt + kSide;
  if (y < 16 || y >= 18 || z < top || z >= top + kArch) return false;
  const bool leg1 = x >= kAt + 10 && x < kAt + 12;
  const bool leg2 = x >= kAt + kSide + kGap + 18 && x < kAt + kSide + kGap + 20;
  const bool beam = z >= top + kArch - 2 && x >= kAt + 10 && x < kAt + kSide + kGap + 20;
  return leg1 || leg2 || beam;
}

// The same arch with both legs on the first box: a handle of web, its top far from the data.
bool Handle(int x, int y, int z) {
  const int top = kAt + kSide;
  if (y < 16 || y >= 18 || z < top || z >= top + kArch) return false;
  const bool leg1 = x >= kAt + 4 && x < kAt + 6;
  const bool leg2 = x >= kAt + 24 && x < kAt + 26;
  const bool beam = z >= top + kArch - 2 && x >= kAt + 4 && x < kAt + 26;
  return leg1 || leg2 || beam;
}

// A small arch on the first box: legs 2 voxels tall, a beam 2 thick over a gap 4 wide, every
// voxel within 4 steps of the box's data through the solid (a web between thin parts that
// come close, left where the voxel is large).
bool LowHandle(int x, int y, int z) {
  const int top = kAt + kSide, a = kAt + 8;
  if (y < 16 || y >= 18 || z < top || z >= top + 4 || x < a || x >= a + 8) return false;
  return z >= top + 2 || x < a + 2 || x >= a + 6;
}

struct Outcome {
  VoxelTopology topology;
  PieceSeparationStats stats;
  int64_t hard_lost = 0;       // hard voxels turned outside
  int64_t interior_lost = 0;   // box interior voxels turned outside
};

Outcome Separate(VoxelGrid& grid, const PieceSeparationOptions& options = {}) {
  const VoxelGrid before = grid;
  absl::StatusOr<PieceSeparationStats> stats =
      SeparateDataPieces(grid, options, CancelToken::Never());
  EXPECT_TRUE(stats.ok()) << stats.status();
  Outcome out;
  if (stats.ok()) out.stats = *stats;
  out.topology = ComputeVoxelTopology(grid);
  for (int64_t v = 0; v < grid.size(); ++v) {
    if (!IsOutside(grid.at(v)) || IsOutside(before.at(v))) continue;
    out.hard_lost += IsHard(before.at(v));
    const Coord c = grid.CoordOf(v);
    out.interior_lost += InBox(c.x, c.y, c.z, kAt) || InBox(c.x, c.y, c.z, kAt + kSide + kGap);
  }
  const absl::Status valid = CheckMembraneInvariants(grid, InvariantOptions{});
  EXPECT_TRUE(valid.ok()) << valid;
  return out;
}

TEST(SeparateDataPieces, APlugBetweenTwoPiecesIsCut) {
  VoxelGrid grid = TwoBoxes(Plug);
  ASSERT_EQ(ComputeVoxelTopology(grid).shells, 1);
  const Outcome out = Separate(grid);
  EXPECT_EQ(out.stats.pieces, 2);
  EXPECT_TRUE(out.stats.separated);
  EXPECT_EQ(out.topology.shells, 2);
  EXPECT_EQ(out.topology.genus, (std::vector<int>{0, 0}));
  EXPECT_EQ(out.topology.cavities, 0);
  EXPECT_EQ(out.hard_lost, 0);
  EXPECT_EQ(out.interior_lost, 0);
  // One layer of the plug's 16-voxel section, not the plug: the rest returns to the solid.
  EXPECT_GE(out.stats.cut_voxels, 16);
  EXPECT_LE(out.stats.cut_voxels, 2 * 16);
}

// The plug and `web` (one handle) between or on the boxes: two shells of genus 0, every hard
// and interior voxel kept.
void ExpectTwoBallsWithPlugAnd(const Predicate& web) {
  VoxelGrid grid = TwoBoxes([&](int x, int y, int z) { return Plug(x, y, z) || web(x, y, z); });
  ASSERT_EQ(ComputeVoxelTopology(grid).genus, std::vector<int>{1});
  const Outcome out = Separate(grid);
  EXPECT_TRUE(out.stats.separated);
  EXPECT_EQ(out.topology.shells, 2);
  EXPECT_EQ(out.topology.genus, (std::vector<int>{0, 0}));
  EXPECT_EQ(out.hard_lost, 0);
  EXPECT_EQ(out.interior_lost, 0);
}

TEST(SeparateDataPieces, AnArchFarFromTheDataIsCutWithThePlug) { ExpectTwoBallsWithPlugAnd(Arch); }

// Without the cut far from the data, the first box would keep the web's handle (genus [0, 1]).
TEST(SeparateDataPieces, AHandleOfWebFarFromTheDataIsCutWithThePlug) {
  ExpectTwoBallsWithPlugAnd(Handle);
}

// A web whose voxels all lie within far_steps of the data keeps its handle through the first
// two trials; the third cuts from near_far_steps and is kept for its fewer handles.
TEST(SeparateDataPieces, AHandleOfWebNearTheDataIsCutFromTheNearerSteps) {
  const auto plug_and_handle = [](int x, int y, int z) {
    return Plug(x, y, z) || LowHandle(x, y, z);
  };
  VoxelGrid grid = TwoBoxes(plug_and_handle);
  ASSERT_EQ(ComputeVoxelTopology(grid).genus, std::vector<int>{1});
  const Outcome out = Separate(grid);
  EXPECT_TRUE(out.stats.separated);
  EXPECT_EQ(out.topology.genus, (std::vector<int>{0, 0}));
  EXPECT_EQ(out.hard_lost, 0);
  EXPECT_EQ(out.interior_lost, 0);

  VoxelGrid without = TwoBoxes(plug_and_handle);
  PieceSeparationOptions two_trials;
  two_trials.near_far_steps = 0;
  const Outcome two = Separate(without, two_trials);
  EXPECT_TRUE(two.stats.separated);
  EXPECT_EQ(two.topology.genus, (std::vector<int>{1, 0}));
}

// Where the first two trials already leave no handle the third trial's larger cut is not
// taken: the grid comes out as it does without it.
TEST(SeparateDataPieces, TheNearerStepsAreNotTakenForNoFewerHandles) {
  VoxelGrid grid = TwoBoxes(Plug);
  Separate(grid);
  VoxelGrid without = TwoBoxes(Plug);
  PieceSeparationOptions two_trials;
  two_trials.near_far_steps = 0;
  Separate(without, two_trials);
  EXPECT_EQ(grid.states(), without.states());
}

// `grid` comes out unchanged, its data counted as `pieces` pieces.
void ExpectLeftAlone(VoxelGrid grid, int pieces) {
  const VoxelStates before = grid.states();
  const Outcome out = Separate(grid);
  EXPECT_EQ(out.stats.pieces, pieces);
  EXPECT_FALSE(out.stats.separated);
  EXPECT_EQ(grid.states(), before);
}

TEST(SeparateDataPieces, APieceWithAWebIsLeftAlone) {
  ExpectLeftAlone(TwoBoxes(Arch, /*second_box=*/false), 1);
}

TEST(SeparateDataPieces, TwoShellsAlreadyApartAreLeftAlone) {
  ExpectLeftAlone(TwoBoxes([](int, int, int) { return false; }), 2);
}

// A ball of radius 15 whose data (a hard skin) miss a band 7 voxels wide around its equator,
// as a sphere seen by two depth cameras front and back: the band is a membrane frozen over a
// data gap. The two caps are two pieces a few voxels apart, as two objects are; the cut between
// them spans the ball's whole cross-section, comparable to a cap's data, while the plug
// between two boxes is a small fraction of a box's data.
TEST(SeparateDataPieces, ACutAcrossAWholeSolidIsRefused) {
  constexpr int kN = 40, kC = 20, kR = 15, kBand = 3;
  VoxelGrid grid({kN, kN, kN}, {0, 0, 0}, 1.0, OutsideState(1));
  for (int z = 1; z + 1 < kN; ++z)
    for (int y = 1; y + 1 < kN; ++y)
      for (int x = 1; x + 1 < kN; ++x) {
        const double r = std::sqrt(double((x - kC) * (x - kC) + (y - kC) * (y - kC) +
                                          (z - kC) * (z - kC)));
        if (r > kR) continue;
        const bool skin = r > kR - 1.5 && std::abs(z - kC) > kBand;
        grid.set(grid.Index(x, y, z), skin ? kInsideHard : kInsideSoft);
      }
  SetFinalMembraneStates(grid);
  ASSERT_EQ(ComputeVoxelTopology(grid).shells, 1);
  const VoxelStates before = grid.states();
  const Outcome out = Separate(grid);
  EXPECT_EQ(out.stats.pieces, 2);
  EXPECT_FALSE(out.stats.separated);
  EXPECT_EQ(out.stats.shells_after, 2);  // the cut alone would pass the topology test
  EXPECT_GT(out.stats.cut_fraction, PieceSeparationOptions{}.max_cut_fraction);
  EXPECT_EQ(grid.states(), before);

  VoxelGrid boxes = TwoBoxes(Plug);
  const Outcome plug = Separate(boxes);
  EXPECT_TRUE(plug.stats.separated);
  EXPECT_LT(plug.stats.cut_fraction, PieceSeparationOptions{}.max_cut_fraction / 10);
}

TEST(SeparateDataPieces, OptionsOutOfRangeAreRefused) {
  VoxelGrid grid = TwoBoxes(Plug);
  PieceSeparationOptions options;
  options.far_steps = 0;
  absl::StatusOr<PieceSeparationStats> stats =
      SeparateDataPieces(grid, options, CancelToken::Never());
  EXPECT_EQ(stats.status().code(), absl::StatusCode::kInvalidArgument);
  options = {};
  options.near_far_steps = options.far_steps;  // must lie below far_steps
  stats = SeparateDataPieces(grid, options, CancelToken::Never());
  EXPECT_EQ(stats.status().code(), absl::StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace membrane

// Pieces of data told apart by their points where their hard voxels touch: two cubes whose
// skins meet at one corner are one 26-component of hard voxels; when their points across that
// corner lie more than two voxels apart they are two pieces, and the piece separation cuts the
// touching hard voxels (each only where its own data's face neighbour stays in the solid);
// points within two voxels across the corner keep them one piece, left alone.
#include "core/engine/point_gap_split.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "core/engine/flat_bitset.h"

#include "core/engine/hard_voxel_points.h"
#include "core/engine/membrane_invariants.h"
#include "core/engine/piece_separation.h"
#include "core/engine/voxel_topology.h"
#include "tests/engine/final_membrane_states.h"

namespace membrane {
namespace point_gap_split_test {  // apart from the other tests of the unity build
namespace {

constexpr int kN = 26;      // grid side
constexpr int kSide = 10;   // each cube's side
constexpr int kFirst = 2;   // the first cube's least voxel on every axis
constexpr int kSecond = kFirst + kSide;  // the second's: the cubes meet at one corner

bool InCube(const Coord& c, int at) {
  return c.x >= at && c.x < at + kSide && c.y >= at && c.y < at + kSide && c.z >= at &&
         c.z < at + kSide;
}

bool OnSkin(const Coord& c, int at) {
  if (!InCube(c, at)) return false;
  for (int d = 0; d < 3; ++d)
    if (c[d] == at || c[d] == at + kSide - 1) return true;
  return false;
}

// The two corner voxels that touch.
const Coord kFirstCorner{kSecond - 1, kSecond - 1, kSecond - 1};
const Coord kSecondCorner{kSecond, kSecond, kSecond};

struct Cubes {
  VoxelGrid grid{{kN, kN, kN}, {0, 0, 0}, 1.0, OutsideState(1)};
  std::vector<Point3f> points;
  int64_t hard = 0;
};

// Two cubes with hard skins (one point at each skin voxel's centre) and soft interiors, as the
// shrink leaves them; the two corner voxels' points lie `offset` voxels from the corner they
// share, along the diagonal into their own voxel. `soft_beside` makes the skin voxels face-
// adjacent to the two corners soft: the corners then have no face neighbour holding data.
Cubes TwoCubes(float offset, bool soft_beside = false) {
  Cubes cubes;
  VoxelGrid& grid = cubes.grid;
  for (int z = 1; z + 1 < kN; ++z)
    for (int y = 1; y + 1 < kN; ++y)
      for (int x = 1; x + 1 < kN; ++x) {
        const Coord c{x, y, z};
        if (!InCube(c, kFirst) && !InCube(c, kSecond)) continue;
        bool skin = OnSkin(c, kFirst) || OnSkin(c, kSecond);
        for (const Coord& corner : {kFirstCorner, kSecondCorner}) {
          const int dist = std::abs(c.x - corner.x) + std::abs(c.y - corner.y) +
                           std::abs(c.z - corner.z);
          if (soft_beside && dist == 1) skin = false;
        }
        grid.set(grid.Index(c), skin ? kInsideHard : kInsideSoft);
        if (!skin) continue;
        ++cubes.hard;
        Point3f p{x + 0.5f, y + 0.5f, z + 0.5f};
        if (c == kFirstCorner) p = {kSecond - offset, kSecond - offset, kSecond - offset};
        if (c == kSecondCorner) p = {kSecond + offset, kSecond + offset, kSecond + offset};
        cubes.points.push_back(p);
      }
  SetFinalMembraneStates(grid);
  return cubes;
}

std::vector<int64_t> HardVoxels(const VoxelGrid& grid) {
  std::vector<int64_t> hard;
  for (int64_t v = 0; v < grid.size(); ++v)
    if (IsHard(grid.at(v))) hard.push_back(v);
  return hard;
}

TEST(SplitAtPointGaps, CornersWhosePointsLieApartSplitTheComponent) {
  Cubes apart = TwoCubes(0.95f);  // the corners' points 3.3 voxels apart
  HardVoxelPoints points(apart.grid, apart.points);
  const std::vector<int64_t> hard = HardVoxels(apart.grid);
  const std::vector<std::vector<int64_t>> parts =
      SplitAtPointGaps(apart.grid, points, hard, 2.0, 100);
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0].size() + parts[1].size(), hard.size());
  EXPECT_EQ(parts[0].size(), parts[1].size());

  Cubes close = TwoCubes(0.05f);  // 0.17 voxel apart: one piece
  HardVoxelPoints close_points(close.grid, close.points);
  EXPECT_EQ(SplitAtPointGaps(close.grid, close_points, HardVoxels(close.grid), 2.0, 100).size(),
            1u);
}

// What FindDataPieces promises, computed the plain way: every 26-component of the hard voxels
// listed breadth first from its least voxel, the big ones kept and each split by
// SplitAtPointGaps.
DataPieces ReferencePieces(const VoxelGrid& grid, const HardVoxelPoints* points, double reach,
                           double min_fraction) {
  std::vector<std::vector<int64_t>> components;
  FlatBitset seen(grid.size());
  int64_t hard = 0;
  for (int64_t i = 0; i < grid.size(); ++i) {
    if (!IsHard(grid.at(i)) || seen.test(i)) continue;
    std::vector<int64_t>& component = components.emplace_back(1, i);
    seen.set(i);
    for (size_t k = 0; k < component.size(); ++k)
      for (int64_t off : grid.neighbour_offsets()) {
        const int64_t n = component[k] + off;
        if (IsHard(grid.at(n)) && !seen.test(n)) {
          seen.set(n);
          component.push_back(n);
        }
      }
    hard += static_cast<int64_t>(component.size());
  }
  DataPieces out;
  if (hard == 0) return out;
  out.min_voxels = static_cast<int64_t>(
      std::ceil(std::max(1.0, min_fraction * static_cast<double>(hard))));
  for (const std::vector<int64_t>& component : components) {
    if (static_cast<int64_t>(component.size()) < out.min_voxels) continue;
    if (points == nullptr || reach <= 0) {
      out.pieces.push_back(component);
      continue;
    }
    std::vector<std::vector<int64_t>> parts =
        SplitAtPointGaps(grid, *points, component, reach, out.min_voxels);
    out.split = out.split || parts.size() > 1;
    for (std::vector<int64_t>& part : parts) out.pieces.push_back(std::move(part));
  }
  out.count = static_cast<int>(out.pieces.size());
  if (out.count < 2) out.pieces.clear();
  return out;
}

// Clumps of hard voxels (random walks, some beside each other) with one to three points each
// anywhere in their voxel: components that touch, classes that split them, strays.
struct Clumps {
  VoxelGrid grid{{30, 30, 30}, {0, 0, 0}, 1.0, kInsideSoft};
  std::vector<Point3f> points;
};

Clumps RandomClumps(uint32_t seed) {
  Clumps clumps;
  VoxelGrid& grid = clumps.grid;
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> coord(3, 26), step(-1, 1), walk(5, 120), clumps_n(2, 7),
      per_voxel(1, 3);
  std::uniform_real_distribution<float> within(0.0f, 0.999f);
  for (int c = clumps_n(rng); c > 0; --c) {
    Coord at{coord(rng), coord(rng), coord(rng)};
    for (int w = walk(rng); w > 0; --w) {
      const int64_t v = grid.Index(at);
      if (!IsHard(grid.at(v))) {
        grid.set(v, kInsideHard);
        for (int p = per_voxel(rng); p > 0; --p)
          clumps.points.push_back({at.x + within(rng), at.y + within(rng), at.z + within(rng)});
      }
      for (int d = 0; d < 3; ++d) at[d] = std::clamp(at[d] + step(rng), 2, 27);
    }
  }
  // The padding is outside.
  for (int64_t v = 0; v < grid.size(); ++v) {
    const Coord c = grid.CoordOf(v);
    for (int d = 0; d < 3; ++d)
      if (c[d] == 0 || c[d] == grid.dim(d) - 1) grid.set(v, OutsideState(1));
  }
  return clumps;
}

void ExpectSamePieces(const VoxelGrid& grid, const HardVoxelPoints* points, double reach,
                      double min_fraction, const std::string& what) {
  const DataPieces want = ReferencePieces(grid, points, reach, min_fraction);
  absl::StatusOr<DataPieces> got =
      FindDataPieces(grid, points, reach, min_fraction, CancelToken::Never());
  ASSERT_TRUE(got.ok()) << got.status();
  EXPECT_EQ(got->count, want.count) << what;
  EXPECT_EQ(got->pieces, want.pieces) << what;
  EXPECT_EQ(got->split, want.split) << what;
  EXPECT_EQ(got->min_voxels, want.min_voxels) << what;
}

TEST(FindDataPieces, TheSamePiecesAsEachComponentSplitBySplitAtPointGaps) {
  int splits = 0, several = 0;
  for (uint32_t seed = 1; seed <= 60; ++seed) {
    const Clumps clumps = RandomClumps(seed);
    const HardVoxelPoints points(clumps.grid, clumps.points);
    for (const double reach : {0.0, 1.0, 2.0, 2.5})
      for (const double fraction : {0.01, 0.1, 0.3}) {
        const std::string what =
            "seed " + std::to_string(seed) + " reach " + std::to_string(reach) + " fraction " +
            std::to_string(fraction);
        ExpectSamePieces(clumps.grid, &points, reach, fraction, what);
        const DataPieces want = ReferencePieces(clumps.grid, &points, reach, fraction);
        splits += want.split;
        several += want.count >= 2;
      }
    ExpectSamePieces(clumps.grid, nullptr, 2.0, 0.01, "no points, seed " + std::to_string(seed));
  }
  // The clumps exercise every way: pieces split at point gaps, several pieces, lone ones.
  EXPECT_GT(splits, 20);
  EXPECT_GT(several, 100);
  EXPECT_LT(several, 60 * 12);
}

TEST(FindDataPieces, TheCubesMeetingAtACornerAreTwoPiecesWhenTheirPointsLieApart) {
  for (const float offset : {0.95f, 0.05f}) {
    Cubes cubes = TwoCubes(offset);
    const HardVoxelPoints points(cubes.grid, cubes.points);
    absl::StatusOr<DataPieces> found =
        FindDataPieces(cubes.grid, &points, 2.0, 0.01, CancelToken::Never());
    ASSERT_TRUE(found.ok()) << found.status();
    EXPECT_EQ(found->count, offset > 0.5f ? 2 : 1);
    EXPECT_EQ(found->split, offset > 0.5f);
    ExpectSamePieces(cubes.grid, &points, 2.0, 0.01, "cubes");
  }
}

TEST(SeparateDataPieces, TouchingHardVoxelsOfTwoPiecesAreCut) {
  Cubes cubes = TwoCubes(0.95f);
  ASSERT_EQ(ComputeVoxelTopology(cubes.grid).shells, 1);  // 26-adjacent at the corner
  HardVoxelPoints points(cubes.grid, cubes.points);
  absl::StatusOr<PieceSeparationStats> stats =
      SeparateDataPieces(cubes.grid, {}, CancelToken::Never(), &points);
  ASSERT_TRUE(stats.ok()) << stats.status();
  EXPECT_EQ(stats->pieces, 2);
  EXPECT_TRUE(stats->separated);
  const VoxelTopology after = ComputeVoxelTopology(cubes.grid);
  EXPECT_EQ(after.shells, 2);
  EXPECT_EQ(after.genus, (std::vector<int>{0, 0}));
  // One corner is enough; each one carved keeps a face neighbour of its cube's skin.
  EXPECT_GE(stats->hard_cut_voxels, 1);
  EXPECT_LE(stats->hard_cut_voxels, 2);
  for (const Coord& corner : {kFirstCorner, kSecondCorner}) {
    if (!IsOutside(cubes.grid.at(cubes.grid.Index(corner)))) continue;
    const int step = corner == kFirstCorner ? -1 : 1;
    EXPECT_TRUE(IsHard(cubes.grid.at(cubes.grid.Index(corner.x + step, corner.y, corner.z))));
  }
  InvariantOptions io;
  io.expected_hard_voxels = cubes.hard - stats->hard_cut_voxels;
  const absl::Status valid = CheckMembraneInvariants(cubes.grid, io);
  EXPECT_TRUE(valid.ok()) << valid;
}

// Without the points, or with points close across the corner, the cubes are one piece.
TEST(SeparateDataPieces, TouchingHardVoxelsWithoutAGapInTheirPointsStay) {
  for (const bool with_points : {false, true}) {
    Cubes cubes = TwoCubes(0.05f);
    const VoxelStates before = cubes.grid.states();
    HardVoxelPoints points(cubes.grid, cubes.points);
    absl::StatusOr<PieceSeparationStats> stats = SeparateDataPieces(
        cubes.grid, {}, CancelToken::Never(), with_points ? &points : nullptr);
    ASSERT_TRUE(stats.ok()) << stats.status();
    EXPECT_EQ(stats->pieces, 1);
    EXPECT_EQ(cubes.grid.states(), before);
  }
}

// Corners whose face neighbours hold no data: carving either would leave its point away from
// every face between its own data and the outside, so no cut is kept.
TEST(SeparateDataPieces, ATouchingHardVoxelWithoutItsDataBesideItStays) {
  Cubes cubes = TwoCubes(0.95f, /*soft_beside=*/true);
  const VoxelStates before = cubes.grid.states();
  HardVoxelPoints points(cubes.grid, cubes.points);
  absl::StatusOr<PieceSeparationStats> stats =
      SeparateDataPieces(cubes.grid, {}, CancelToken::Never(), &points);
  ASSERT_TRUE(stats.ok()) << stats.status();
  EXPECT_EQ(stats->pieces, 2);
  EXPECT_FALSE(stats->separated);
  EXPECT_EQ(cubes.grid.states(), before);
}

}  // namespace
}  // namespace point_gap_split_test
}  // namespace membrane

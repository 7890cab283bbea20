// A chain generation's passes after its first take their snapshot only near the voxels the
// pass before wrote (core/engine/local_snapshot.h): every pass must have the dense snapshot's
// candidates and places, so that the shrink is the same voxel for voxel.
#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "core/engine/contraction.h"
#include "core/engine/membrane_shrinker.h"
#include "core/engine/place_finder.h"
#include "core/engine/voxelization.h"
#include "core/engine/work_planes.h"
#include "core/io/point_cloud_io.h"
#include "gtest/gtest.h"
#include "tests/support/random_membrane.h"
#include "tests/support/shared_data.h"
#include "tests/support/shrink_fixture.h"

namespace membrane {
namespace {

using testing::ShrinkCloud;
using testing::SynthCloud;

// Every later pass local (no set of bricks reaches this share of the grid), in bricks of
// `brick` voxels, or `brick_plates` plates when that is wider: small bricks leave out most of
// the grid, so that a candidate or an anchor missed near the writes shows.
LocalSnapshotOptions AlwaysLocal(int brick, int brick_plates = 0) {
  return {.max_share = 1000, .brick = brick, .brick_plates = brick_plates};
}

// Expects `local`'s last snapshot to have given `candidates`, the dense snapshot's, and the
// dense snapshot's place for each of them; `at` says where.
void ExpectSamePlaces(const PlaceFinder& local, const PlaceFinder& dense,
                      const std::vector<int64_t>& candidates,
                      const std::vector<int64_t>& expected, const std::string& at) {
  EXPECT_EQ(candidates, expected) << at;
  for (int64_t index : expected) {
    const std::optional<Plate> a = local.PlaceFor(index), b = dense.PlaceFor(index);
    ASSERT_TRUE(b.has_value()) << at << ", voxel " << index;
    ASSERT_TRUE(a.has_value()) << at << ", voxel " << index;
    EXPECT_TRUE(a->orientation == b->orientation && a->layer == b->layer && a->u0 == b->u0 &&
                a->v0 == b->v0)
        << at << ", voxel " << index;
  }
}

// Runs generations of chains of plate sizes `sizes` on `grid` as MembraneShrinker::RunChains
// does, taking each pass's snapshot both near the last pass's writes and densely: the same
// candidates and, for each, the same place. The local snapshots' bricks are computed on
// `threads` threads, the dense snapshot on one. Returns the passes whose snapshot was local.
int ExpectLocalPassesAsDense(VoxelGrid& grid, const std::vector<int>& sizes, int brick,
                             int threads = 1, int brick_plates = 0) {
  WorkPlanes planes(grid, threads), dense_planes(grid);
  PlaceFinder finder(grid, planes), dense(grid, dense_planes);
  ChainRunner runner(grid);
  ChainCounters counters;
  const CancelToken cancel;
  int local_passes = 0;
  for (size_t g = 0; g < sizes.size(); ++g) {
    ChainOptions chain;
    chain.generation_label = static_cast<int>(g) + 1;
    chain.guard.plate_size = sizes[g];
    std::vector<VoxelBox> written;
    for (bool first = true;; first = false) {
      const std::optional<std::vector<int64_t>> candidates =
          first ? finder.Snapshot(sizes[g], cancel)
                : finder.SnapshotAfter(sizes[g], written, AlwaysLocal(brick, brick_plates),
                                       cancel);
      const std::optional<std::vector<int64_t>> expected = dense.Snapshot(sizes[g], cancel);
      if (!candidates || !expected) {
        ADD_FAILURE() << "a snapshot failed";
        return local_passes;
      }
      const std::string at = absl::StrCat("bricks of ", brick, " (", brick_plates, " plates) on ",
                                          threads,
                                          " thread(s), n = ", sizes[g],
                                          (first ? ", first pass" : ", a later pass"),
                                          (finder.local() ? " (local)" : " (dense)"));
      local_passes += finder.local() ? 1 : 0;
      ExpectSamePlaces(finder, dense, *candidates, *expected, at);
      written.clear();
      bool changed = false;
      for (int64_t index : *candidates) {
        if (grid.at(index) != kBoundarySoft) continue;
        const std::optional<Plate> plate = finder.PlaceFor(index);
        if (!plate) continue;
        const ChainOutcome outcome = runner.Run(*plate, chain, cancel, counters);
        if (outcome == ChainOutcome::kSkipped) continue;
        changed = true;
        written.insert(written.end(), runner.last_written().begin(),
                       runner.last_written().end());
      }
      if (!changed) break;
    }
  }
  return local_passes;
}

TEST(LocalSnapshots, EveryPassHasTheDenseCandidatesAndPlaces) {
  // Chains from the data box inwards, small plates only: many passes, writes all over.
  const PointCloud cloud = SynthCloud("two-spheres", 12000);
  for (int brick : {2, 5, 32}) {
    absl::StatusOr<Voxelization> voxels = Voxelize(cloud.points, {});
    ASSERT_TRUE(voxels.ok()) << voxels.status();
    EXPECT_GT(ExpectLocalPassesAsDense(voxels->grid, {7, 5, 3, 2, 1}, brick), 3);
  }
}

TEST(LocalSnapshots, BricksOnThreadsHaveTheDenseCandidatesAndPlaces) {
  // Small bricks: hundreds of them a pass, split in ranges over the threads.
  const PointCloud cloud = SynthCloud("two-spheres", 12000);
  for (int threads : {2, 3}) {
    for (int brick : {2, 5}) {
      absl::StatusOr<Voxelization> voxels = Voxelize(cloud.points, {});
      ASSERT_TRUE(voxels.ok()) << voxels.status();
      EXPECT_GT(ExpectLocalPassesAsDense(voxels->grid, {7, 5, 3, 2, 1}, brick, threads), 3);
    }
  }
}

TEST(LocalSnapshots, EveryPassHasTheDenseCandidatesAndPlacesOnASparseTorus) {
  // Half the formula-(1) voxel: gaps in the data, backtracks and frozen plates.
  const PointCloud cloud = SynthCloud("torus", 20000);
  absl::StatusOr<Voxelization> first = Voxelize(cloud.points, {});
  ASSERT_TRUE(first.ok()) << first.status();
  VoxelizeOptions options;
  options.voxel_size = first->grid.voxel_size() * 0.5;
  for (int brick : {3, 16}) {
    absl::StatusOr<Voxelization> voxels = Voxelize(cloud.points, options);
    ASSERT_TRUE(voxels.ok()) << voxels.status();
    EXPECT_GT(ExpectLocalPassesAsDense(voxels->grid, {6, 4, 2, 1}, brick), 3);
  }
}

TEST(LocalSnapshots, EveryPlateSizeHasTheDenseCandidatesAndPlaces) {
  // Every plate size from 13 down, in bricks narrower than their margins and in bricks of
  // four plates (the shrink's): the anchor rows of n >= 8 only skip rows without anchors.
  const PointCloud cloud = SynthCloud("two-spheres", 12000);
  std::vector<int> sizes(13);
  for (int k = 0; k < 13; ++k) sizes[static_cast<size_t>(k)] = 13 - k;
  for (const auto& [brick, plates] : {std::pair{2, 0}, std::pair{32, 4}}) {
    absl::StatusOr<Voxelization> voxels = Voxelize(cloud.points, {});
    ASSERT_TRUE(voxels.ok()) << voxels.status();
    EXPECT_GT(ExpectLocalPassesAsDense(voxels->grid, sizes, brick, /*threads=*/2, plates), 13);
  }
}

// A grid of `dims` voxels in which plates of every size up to 13 fit: outside on the two outer
// layers and in random boxes and balls, boundary soft next to the outside, a random few
// boundary voxels hard or frozen and a random few voxels anywhere outside or boundary soft.
VoxelGrid RandomGrid(const std::array<int, 3>& dims, uint32_t seed) {
  VoxelGrid grid(dims, {0, 0, 0}, 1.0);
  std::mt19937 rng(seed);
  auto uniform = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  for (int k = 0; k < 6; ++k) {
    Coord lo, hi;
    for (int d = 0; d < 3; ++d) {
      lo[d] = uniform(2, dims[d] - 4);
      hi[d] = std::min(lo[d] + uniform(1, 30), dims[d] - 3);
    }
    const Coord centre{uniform(2, dims[0] - 3), uniform(2, dims[1] - 3), uniform(2, dims[2] - 3)};
    const int r = uniform(2, 14);
    for (int z = 0; z < dims[2]; ++z)
      for (int y = 0; y < dims[1]; ++y)
        for (int x = 0; x < dims[0]; ++x) {
          const Coord c{x, y, z};
          const int dx = x - centre.x, dy = y - centre.y, dz = z - centre.z;
          bool in_box = true;
          for (int d = 0; d < 3; ++d) in_box = in_box && c[d] >= lo[d] && c[d] <= hi[d];
          const bool border = std::min({x, y, z, dims[0] - 1 - x, dims[1] - 1 - y,
                                        dims[2] - 1 - z}) < 2;
          if (in_box || border || dx * dx + dy * dy + dz * dz <= r * r) {
            grid.set(c, OutsideState(uniform(0, 3)));
          }
        }
  }
  testing::MarkRandomMembrane(grid, rng, 200);
  return grid;
}

TEST(LocalSnapshots, RandomGridsHaveTheDenseCandidatesAndPlaces) {
  // Written everywhere: every brick is computed on its own box, and each of its candidates
  // must find the dense snapshot's place there, for every plate size and brick width.
  const CancelToken cancel;
  for (uint32_t seed : {1u, 2u, 3u}) {
    const VoxelGrid grid = RandomGrid({61, 53, 47}, seed);
    VoxelBox everywhere;
    everywhere.Add({0, 0, 0});
    everywhere.Add({60, 52, 46});
    const int threads = 1 + static_cast<int>(seed % 2);
    WorkPlanes planes(grid, threads), dense_planes(grid);
    PlaceFinder finder(grid, planes), dense(grid, dense_planes);
    for (int n = 1; n <= 13; ++n) {
      for (const auto& [brick, plates] : {std::pair{5, 0}, std::pair{1, 4}}) {
        const std::string at = absl::StrCat("seed ", seed, ", ", threads, " thread(s), n = ", n,
                                            ", bricks of ", brick, " (", plates, " plates)");
        ASSERT_TRUE(finder.Snapshot(n, cancel));
        const std::optional<std::vector<int64_t>> candidates =
            finder.SnapshotAfter(n, {everywhere}, AlwaysLocal(brick, plates), cancel);
        const std::optional<std::vector<int64_t>> expected = dense.Snapshot(n, cancel);
        ASSERT_TRUE(candidates && expected) << at;
        EXPECT_TRUE(finder.local()) << at;
        EXPECT_FALSE(expected->empty()) << at;
        ExpectSamePlaces(finder, dense, *candidates, *expected, at);
      }
    }
  }
}

TEST(LocalSnapshots, RandomGridsPassByPassHaveTheDenseCandidatesAndPlaces) {
  // Chains of every plate size from 13 down on random grids: hard and frozen voxels on the
  // boundary, lone outside and boundary voxels, many backtracks.
  std::vector<int> sizes(13);
  for (int k = 0; k < 13; ++k) sizes[static_cast<size_t>(k)] = 13 - k;
  for (uint32_t seed : {4u, 5u}) {
    for (const auto& [brick, plates] : {std::pair{3, 0}, std::pair{8, 4}}) {
      VoxelGrid grid = RandomGrid({61, 53, 47}, seed);
      EXPECT_GT(ExpectLocalPassesAsDense(grid, sizes, brick, /*threads=*/1, plates), 13)
          << "seed " << seed;
    }
  }
}

// Shrinks `cloud` at `factor` with and without local snapshots: the same states and
// generations.
void ExpectSameShrink(const PointCloud& cloud, double factor, ShrinkOptions options,
                      const std::string& what) {
  options.local_snapshots.max_share = 0;
  auto dense = ShrinkCloud(cloud, factor, options);
  ASSERT_TRUE(dense.ok()) << what << ": " << dense.status();
  for (const auto& [brick, plates] : {std::pair{3, 0}, std::pair{32, 4}}) {
    options.local_snapshots = AlwaysLocal(brick, plates);
    auto local = ShrinkCloud(cloud, factor, options);
    ASSERT_TRUE(local.ok()) << what << ": " << local.status();
    EXPECT_TRUE(local->voxels.grid.states() == dense->voxels.grid.states())
        << what << ", bricks of " << brick << " (" << plates << " plates)";
    ASSERT_EQ(local->result.generations.size(), dense->result.generations.size()) << what;
    for (size_t g = 0; g < dense->result.generations.size(); ++g) {
      const GenerationStats& a = dense->result.generations[g];
      const GenerationStats& b = local->result.generations[g];
      const std::string at =
          absl::StrCat(what, ", bricks of ", brick, ", generation ", a.generation);
      EXPECT_EQ(b.passes, a.passes) << at;
      EXPECT_EQ(b.started_contractions, a.started_contractions) << at;
      EXPECT_EQ(b.backtrackings, a.backtrackings) << at;
      EXPECT_EQ(b.contractions, a.contractions) << at;
      EXPECT_EQ(b.undone_contractions, a.undone_contractions) << at;
      EXPECT_EQ(b.new_outside, a.new_outside) << at;
    }
  }
}

TEST(LocalSnapshots, TorusShrinksTheSame) {
  ExpectSameShrink(SynthCloud("torus", 100000), 1.0, {}, "torus");
}

TEST(LocalSnapshots, ChainsOnlyShrinkTheSame) {
  ShrinkOptions options;
  options.closed_form_min_plate = 0;
  ExpectSameShrink(SynthCloud("two-spheres", 20000), 0.5, options, "two-spheres at 0.5x");
}

TEST(LocalSnapshots, RealScanShrinksTheSame) {
  MEMBRANE_REQUIRE_SHARED_DATA(data_dir);
  absl::StatusOr<PointCloud> cloud = ReadPointCloud(data_dir + "/clouds/rocker-arm-scan.ply");
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  ExpectSameShrink(*cloud, 0.75, {}, "rocker-arm-scan at 0.75x");
}

}  // namespace
}  // namespace membrane

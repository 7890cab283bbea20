// A chain generation's passes after its first take their snapshot only near the voxels the
// pass before wrote (core/engine/local_snapshot.h): every pass must have the dense snapshot's
// candidates and places, so that the shrink is the same voxel for voxel.
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
#include "tests/support/shared_data.h"
#include "tests/support/shrink_fixture.h"

namespace membrane {
namespace {

using testing::ShrinkCloud;
using testing::SynthCloud;

// Every later pass local (no set of bricks reaches this share of the grid), in bricks of
// `brick` voxels: small bricks leave out most of the grid, so that a candidate or an anchor
// missed near the writes shows.
LocalSnapshotOptions AlwaysLocal(int brick) { return {.max_share = 1000, .brick = brick}; }

// Runs generations of chains of plate sizes `sizes` on `grid` as MembraneShrinker::RunChains
// does, taking each pass's snapshot both near the last pass's writes and densely: the same
// candidates and, for each, the same place. The local snapshots' bricks are computed on
// `threads` threads, the dense snapshot on one. Returns the passes whose snapshot was local.
int ExpectLocalPassesAsDense(VoxelGrid& grid, const std::vector<int>& sizes, int brick,
                             int threads = 1) {
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
                : finder.SnapshotAfter(sizes[g], written, AlwaysLocal(brick), cancel);
      const std::optional<std::vector<int64_t>> expected = dense.Snapshot(sizes[g], cancel);
      if (!candidates || !expected) {
        ADD_FAILURE() << "a snapshot failed";
        return local_passes;
      }
      const std::string at = absl::StrCat("bricks of ", brick, " on ", threads,
                                          " thread(s), n = ", sizes[g],
                                          (first ? ", first pass" : ", a later pass"),
                                          (finder.local() ? " (local)" : " (dense)"));
      EXPECT_EQ(*candidates, *expected) << at;
      local_passes += finder.local() ? 1 : 0;
      for (int64_t index : *expected) {
        const std::optional<Plate> a = finder.PlaceFor(index), b = dense.PlaceFor(index);
        EXPECT_EQ(a.has_value(), b.has_value()) << at << ", voxel " << index;
        if (!a || !b) continue;
        EXPECT_TRUE(a->orientation == b->orientation && a->layer == b->layer && a->u0 == b->u0 &&
                    a->v0 == b->v0)
            << at << ", voxel " << index;
      }
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

// Shrinks `cloud` at `factor` with and without local snapshots: the same states and
// generations.
void ExpectSameShrink(const PointCloud& cloud, double factor, ShrinkOptions options,
                      const std::string& what) {
  options.local_snapshots.max_share = 0;
  auto dense = ShrinkCloud(cloud, factor, options);
  ASSERT_TRUE(dense.ok()) << what << ": " << dense.status();
  for (int brick : {3, 32}) {
    options.local_snapshots = AlwaysLocal(brick);
    auto local = ShrinkCloud(cloud, factor, options);
    ASSERT_TRUE(local.ok()) << what << ": " << local.status();
    EXPECT_TRUE(local->voxels.grid.states() == dense->voxels.grid.states())
        << what << ", bricks of " << brick;
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

// The shrink on several threads (ShrinkOptions::threads) gives the states one thread gives:
// the word passes of the closed form and the place finder and the state counts are split by
// the grid, never by the count. Grids of several word blocks (core/engine/word_blocks.h), so
// that the passes do run on several threads.
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "core/engine/membrane_invariants.h"
#include "core/engine/membrane_shrinker.h"
#include "core/engine/voxelization.h"
#include "core/engine/word_blocks.h"
#include "core/io/point_cloud_io.h"
#include "gtest/gtest.h"
#include "tests/support/shared_data.h"
#include "tests/support/shrink_fixture.h"

namespace membrane {
namespace {

using testing::ShrinkCloud;
using testing::SynthCloud;

// Shrinks `cloud` at `factor` with `options` on 1, 2 and 3 threads: the same states, the same
// generations.
void ExpectSameShrinkForAnyThreadCount(const PointCloud& cloud, double factor,
                                       const std::string& what, ShrinkOptions options = {}) {
  options.threads_min_voxels = 0;  // these grids are under the default
  auto one = ShrinkCloud(cloud, factor, options);
  ASSERT_TRUE(one.ok()) << what << ": " << one.status();
  ASSERT_GE(WordBlockCount(2, (one->voxels.grid.size() + 63) / 64), 2) << what;
  ASSERT_TRUE(one->invariants.ok()) << what;
  for (int threads : {2, 3}) {
    options.threads = threads;
    auto many = ShrinkCloud(cloud, factor, options);
    ASSERT_TRUE(many.ok()) << what << ": " << many.status();
    const std::string at = absl::StrCat(what, " on ", threads, " threads");
    EXPECT_TRUE(many->voxels.grid.states() == one->voxels.grid.states()) << at;
    ASSERT_EQ(many->result.generations.size(), one->result.generations.size()) << at;
    for (size_t g = 0; g < one->result.generations.size(); ++g) {
      const GenerationStats& a = one->result.generations[g];
      const GenerationStats& b = many->result.generations[g];
      EXPECT_EQ(b.closed_form, a.closed_form) << at << ", generation " << a.generation;
      EXPECT_EQ(b.closed_form_rounds, a.closed_form_rounds) << at << ", generation " << a.generation;
      EXPECT_EQ(b.new_outside, a.new_outside) << at << ", generation " << a.generation;
      // The closed form's checks run on spans, counted as the scan in order counts them.
      EXPECT_EQ(b.closed_form_checks, a.closed_form_checks)
          << at << ", generation " << a.generation;
      EXPECT_EQ(b.soft_voxels, a.soft_voxels) << at << ", generation " << a.generation;
      EXPECT_EQ(b.contractions, a.contractions) << at << ", generation " << a.generation;
    }
    // The passes after the generations read the grid on the threads too.
    EXPECT_EQ(many->result.refill.refilled_voxels, one->result.refill.refilled_voxels) << at;
    EXPECT_EQ(many->result.post_process.bridge_voxels, one->result.post_process.bridge_voxels)
        << at;
    EXPECT_EQ(many->result.post_process.carved_voxels, one->result.post_process.carved_voxels)
        << at;
    EXPECT_EQ(many->topology.shells, one->topology.shells) << at;
    EXPECT_EQ(many->topology.genus, one->topology.genus) << at;
  }
}

TEST(ShrinkThreads, TorusIsTheSameForAnyThreadCount) {
  // 250k points: a 211^3 grid, four word blocks.
  ExpectSameShrinkForAnyThreadCount(SynthCloud("torus", 250000), 1.0, "torus");
}

TEST(ShrinkThreads, SparseTwoSpheresAreTheSameForAnyThreadCount) {
  // Half the formula-(1) voxel: gaps in the data, so the chains and the guard run too.
  ExpectSameShrinkForAnyThreadCount(SynthCloud("two-spheres", 40000), 0.5, "two-spheres");
}

TEST(ShrinkThreads, RejectedClosedFormsAreRestoredOnAnyThreadCount) {
  // The capped sphere's checks refuse a closed form; applied by planes, its restore runs on
  // blocks of words (250k points: a grid of several word blocks).
  ShrinkOptions by_planes;
  by_planes.closed_form_voxelwise_ratio = 0;
  const PointCloud cloud = SynthCloud("capped-sphere", 250000);
  auto one = ShrinkCloud(cloud, 1.0, by_planes);
  ASSERT_TRUE(one.ok()) << one.status();
  int rejected = 0;
  for (const GenerationStats& g : one->result.generations)
    rejected += !g.closed_form && g.closed_form_rounds > 0;
  ASSERT_GT(rejected, 0);
  ExpectSameShrinkForAnyThreadCount(cloud, 1.0, "capped-sphere by planes", by_planes);
}

TEST(ShrinkThreads, RealScanIsTheSameForAnyThreadCount) {
  MEMBRANE_REQUIRE_SHARED_DATA(data_dir);
  absl::StatusOr<PointCloud> cloud = ReadPointCloud(data_dir + "/clouds/rocker-arm-scan.ply");
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  ExpectSameShrinkForAnyThreadCount(*cloud, 0.75, "rocker-arm-scan at 0.75x");
}

TEST(ShrinkThreads, CancelStopsTheShrinkOnSeveralThreads) {
  const PointCloud cloud = SynthCloud("torus", 250000);
  absl::StatusOr<Voxelization> voxels = Voxelize(cloud.points, {});
  ASSERT_TRUE(voxels.ok()) << voxels.status();
  ShrinkOptions options;
  options.threads = 2;
  options.threads_min_voxels = 0;
  CancelToken cancel;
  // Fired when the first generation ends: the second sees it.
  int generations = 0;
  absl::StatusOr<ShrinkResult> result = ShrinkMembrane(
      voxels->grid, cloud.points, options,
      [&](const GenerationStats&) {
        ++generations;
        cancel.Cancel();
      },
      cancel);
  EXPECT_EQ(result.status().code(), absl::StatusCode::kCancelled) << result.status();
  EXPECT_EQ(generations, 1);
  InvariantOptions io;
  io.require_property3 = false;
  EXPECT_TRUE(CheckMembraneInvariants(voxels->grid, io).ok());
}

TEST(ShrinkThreads, ThreadsOutOfRangeAreRefused) {
  ShrinkOptions options;
  for (int threads : {0, 257}) {
    options.threads = threads;
    EXPECT_EQ(ShrinkCloud(SynthCloud("sphere", 2000), 1.0, options).status().code(),
              absl::StatusCode::kInvalidArgument)
        << threads;
  }
  options.threads = 2;
  options.threads_min_voxels = -1;
  EXPECT_EQ(ShrinkCloud(SynthCloud("sphere", 2000), 1.0, options).status().code(),
            absl::StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace membrane

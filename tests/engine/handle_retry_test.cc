// The handle retry (docs/engine-decisions.md): when the shrink ends with handles, the late
// generations run again under stricter tunnel sizes, and the result with fewer handles and no
// fewer shells is kept. The real case it exists for is the spot scan (real_scans_test.cc);
// here the strict sizes are pushed to "no tunnel away from the data at all" so that a torus
// shows the mechanism on a shape the test makes.
#include "absl/status/status.h"
#include "core/engine/membrane_shrinker.h"
#include "core/engine/plate_schedule.h"
#include "core/engine/voxelization.h"
#include "gtest/gtest.h"
#include "tests/support/shrink_fixture.h"

namespace membrane {
namespace {

using testing::ShrinkCloud;
using testing::SynthCloud;

constexpr int64_t kRetryPoints = 60000;

// Strict sizes no plate reaches: the retry then refuses every tunnel away from hard voxels,
// and its result is kept whatever it hangs on. No plugged hole is opened after it: these tests
// read the retry's own result (the hole opening reopens the torus's hole it spans).
ShrinkOptions NoTunnelRetry() {
  ShrinkOptions o;
  o.retry.tunnel_min_plate = 100000;
  o.retry.short_loop_min_plate = 100000;
  o.retry.max_hard_rim = 2.0;
  o.holes.enabled = false;
  return o;
}

TEST(HandleRetryTest, KeepsTheResultWithFewerHandles) {
  const PointCloud torus = SynthCloud("torus", kRetryPoints);
  ShrinkOptions off = NoTunnelRetry();
  off.retry.enabled = false;
  auto first = ShrinkCloud(torus, 1.0, off);
  ASSERT_TRUE(first.ok()) << first.status();
  ASSERT_EQ(first->topology.genus, std::vector<int>{1}) << first->Describe();
  EXPECT_FALSE(first->result.handle_retry.ran);

  auto retried = ShrinkCloud(torus, 1.0, NoTunnelRetry());
  ASSERT_TRUE(retried.ok()) << retried.status();
  const HandleRetry& r = retried->result.handle_retry;
  EXPECT_GT(r.loose_tunnels, 0);
  EXPECT_TRUE(r.ran);
  EXPECT_TRUE(r.kept);
  EXPECT_EQ(r.shells_before, 1);
  EXPECT_EQ(r.genus_before, 1);
  EXPECT_EQ(r.shells_after, 1);
  EXPECT_EQ(r.genus_after, 0);
  // The hole spanned by a membrane: what the grid holds is what the retry reported.
  EXPECT_EQ(retried->topology.shells, 1) << retried->Describe();
  EXPECT_EQ(retried->topology.genus, std::vector<int>{0}) << retried->Describe();
  EXPECT_TRUE(retried->invariants.ok()) << retried->Describe();
  // One row per plate size, whichever run each came from.
  ASSERT_EQ(retried->result.generations.size(), first->result.generations.size());
  for (size_t g = 0; g < first->result.generations.size(); ++g) {
    EXPECT_EQ(retried->result.generations[g].plate_size, first->result.generations[g].plate_size);
  }
  EXPECT_GE(r.from_generation, 1);
}

TEST(HandleRetryTest, ReportsTheKeptRowsAfterTheFirstRunsRows) {
  absl::StatusOr<Voxelization> vox = Voxelize(SynthCloud("torus", kRetryPoints).points, {});
  ASSERT_TRUE(vox.ok()) << vox.status();
  std::vector<GenerationStats> seen;
  absl::StatusOr<ShrinkResult> result =
      ShrinkMembrane(vox->grid, NoTunnelRetry(),
                     [&seen](const GenerationStats& g) { seen.push_back(g); }, CancelToken::Never());
  ASSERT_TRUE(result.ok()) << result.status();
  ASSERT_TRUE(result->handle_retry.kept);
  const size_t planned = result->generations.size();
  const int from = result->handle_retry.from_generation;
  ASSERT_EQ(seen.size(), planned + (planned - from + 1));
  for (size_t i = 0; i < planned; ++i) {
    EXPECT_EQ(seen[i].generation, static_cast<int>(i) + 1);
    EXPECT_FALSE(seen[i].handle_retry);
  }
  // Then the retry's rows, which are what the result holds from `from` on.
  for (size_t i = planned; i < seen.size(); ++i) {
    const GenerationStats& kept = result->generations[seen[i].generation - 1];
    EXPECT_TRUE(seen[i].handle_retry);
    EXPECT_EQ(seen[i].generation, from + static_cast<int>(i - planned));
    EXPECT_TRUE(kept.handle_retry);
    EXPECT_EQ(kept.started_contractions, seen[i].started_contractions);
  }
  for (int g = 0; g < from - 1; ++g) EXPECT_FALSE(result->generations[g].handle_retry);
}

TEST(HandleRetryTest, StartsAtTheFirstGenerationThatMadeALooseTunnel) {
  // The generations before it made the same removals under either rules: running them again
  // would only repeat them.
  absl::StatusOr<Voxelization> vox = Voxelize(SynthCloud("torus", kRetryPoints).points, {});
  ASSERT_TRUE(vox.ok()) << vox.status();
  std::vector<GenerationStats> seen;
  absl::StatusOr<ShrinkResult> result =
      ShrinkMembrane(vox->grid, NoTunnelRetry(),
                     [&seen](const GenerationStats& g) { seen.push_back(g); }, CancelToken::Never());
  ASSERT_TRUE(result.ok()) << result.status();
  ASSERT_TRUE(result->handle_retry.ran);
  const int from = result->handle_retry.from_generation;
  ASSERT_GE(from, 1);
  ASSERT_LE(from, static_cast<int>(seen.size()));
  EXPECT_GT(seen[from - 1].loose_tunnels, 0);
  for (int g = 0; g < from - 1; ++g) EXPECT_EQ(seen[g].loose_tunnels, 0) << "generation " << g + 1;
}

TEST(HandleRetryTest, ACancelBeforeTheRetryStopsIt) {
  // Cancelled as the first run's last generation is reported: the retry's topology count and
  // copies poll the token, so the shrink ends Cancelled before running anything again.
  absl::StatusOr<Voxelization> vox = Voxelize(SynthCloud("torus", kRetryPoints).points, {});
  ASSERT_TRUE(vox.ok()) << vox.status();
  CancelToken cancel;
  int reported = 0;
  absl::StatusOr<ShrinkResult> result = ShrinkMembrane(
      vox->grid, NoTunnelRetry(),
      [&](const GenerationStats& g) {
        ++reported;
        if (g.plate_size == 1) cancel.Cancel();
      },
      cancel);
  EXPECT_EQ(result.status().code(), absl::StatusCode::kCancelled) << result.status();
  EXPECT_NE(result.status().message().find("handle retry"), std::string::npos)
      << result.status();
  // No retry row was reported.
  const size_t planned = PlateSizes(vox->data_dims, PlateSchedule::kHalving, 0).size();
  EXPECT_EQ(reported, static_cast<int>(planned));
}

TEST(HandleRetryTest, KeepsAScannedHoleOpen) {
  // At 2.5x the formula-(1) size the tilted torus's hole opens only at a plate of 6, which the
  // strict sizes refuse: the retry spans the hole with a membrane whose rim is the hole's
  // scanned edge, and that result is not kept.
  auto run = ShrinkCloud(SynthCloud("torus", kRetryPoints), 2.5);
  ASSERT_TRUE(run.ok()) << run.status();
  const HandleRetry& r = run->result.handle_retry;
  EXPECT_TRUE(r.ran);
  EXPECT_FALSE(r.kept);
  EXPECT_GT(r.web_voxels, 0);
  EXPECT_GE(r.web_hard_rim, ShrinkOptions{}.retry.max_hard_rim);
  EXPECT_EQ(run->topology.genus, std::vector<int>{1}) << run->Describe();
  EXPECT_TRUE(run->invariants.ok()) << run->Describe();
}

TEST(HandleRetryTest, TransientTunnelsOfASplitNeedNoRetry) {
  // Two spheres split through a tunnel that closes again: no handle is left, so nothing runs
  // again, and the split stays.
  const PointCloud spheres = SynthCloud("two-spheres", kRetryPoints);
  auto run = ShrinkCloud(spheres, 1.5, NoTunnelRetry());
  ASSERT_TRUE(run.ok()) << run.status();
  EXPECT_EQ(run->topology.shells, 2) << run->Describe();
  EXPECT_FALSE(run->result.handle_retry.ran);
  EXPECT_TRUE(run->invariants.ok()) << run->Describe();
}

TEST(HandleRetryTest, NeverTradesAShellForAHandle) {
  // A torus beside the two spheres: the handle makes the retry run, and without tunnels the
  // spheres do not split. One handle fewer for one shell fewer is refused.
  const PointCloud spheres = SynthCloud("two-spheres", kRetryPoints);
  const double voxel = 1.5 * EstimateVoxelSize(*CheckedBounds(spheres.points), kRetryPoints);
  PointCloud both = spheres;
  for (Point3f p : SynthCloud("torus", kRetryPoints).points) {
    p[0] += 6.0f;
    both.points.push_back(p);
  }
  ShrinkOptions off = NoTunnelRetry();
  off.retry.enabled = false;
  auto first = ShrinkCloud(both, 1.0, off, voxel);
  ASSERT_TRUE(first.ok()) << first.status();
  ASSERT_EQ(first->topology.shells, 3) << first->Describe();
  auto run = ShrinkCloud(both, 1.0, NoTunnelRetry(), voxel);
  ASSERT_TRUE(run.ok()) << run.status();
  const HandleRetry& r = run->result.handle_retry;
  EXPECT_TRUE(r.ran);
  EXPECT_FALSE(r.kept) << "retry: shells " << r.shells_after << ", genus " << r.genus_after;
  EXPECT_EQ(run->topology.shells, 3) << run->Describe();
  EXPECT_EQ(run->topology.genus, first->topology.genus) << run->Describe();
  EXPECT_TRUE(run->invariants.ok()) << run->Describe();
}

TEST(HandleRetryTest, SameSizesMeanNoRetry) {
  // With the strict sizes equal to the default ones no removal differs: the run would repeat.
  ShrinkOptions o;
  o.retry.tunnel_min_plate = o.guard.tunnel_min_plate;
  o.retry.short_loop_min_plate = o.guard.short_loop_min_plate;
  o.retry.wall_notch_min_plate = o.guard.wall_notch_min_plate;
  auto run = ShrinkCloud(SynthCloud("torus", kRetryPoints), 1.0, o);
  ASSERT_TRUE(run.ok()) << run.status();
  EXPECT_EQ(run->topology.genus, std::vector<int>{1}) << run->Describe();
  EXPECT_FALSE(run->result.handle_retry.ran);
  EXPECT_EQ(run->result.handle_retry.loose_tunnels, 0);
  for (const GenerationStats& g : run->result.generations) EXPECT_EQ(g.loose_tunnels, 0);
}

TEST(HandleRetryTest, RejectsOutOfRangeSizes) {
  ShrinkOptions o;
  o.retry.tunnel_min_plate = 0;
  absl::Status s = ValidateShrinkOptions(o);
  EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("retry_tunnel_min_plate"), std::string::npos) << s;
  o = ShrinkOptions{};
  o.retry.short_loop_min_plate = -1;
  s = ValidateShrinkOptions(o);
  EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("retry_short_loop_min_plate"), std::string::npos) << s;
  o = ShrinkOptions{};
  o.retry.max_hard_rim = -0.5;
  s = ValidateShrinkOptions(o);
  EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("retry_max_hard_rim"), std::string::npos) << s;
}

}  // namespace
}  // namespace membrane

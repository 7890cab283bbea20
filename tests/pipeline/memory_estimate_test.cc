// The estimates the memory budget and the --local memory limit refuse jobs on.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "absl/strings/str_format.h"
#include "core/engine/voxelization.h"
#include "core/pipeline/memory_estimate.h"
#include "core/synth/synthesize.h"

namespace membrane::testing {
namespace {

TEST(PlanGrid, PlansTheGridVoxelizeAllocates) {
  absl::StatusOr<PointCloud> cloud =
      SynthesizeShape(SynthOptions{.shape = "torus", .points = 20000});
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  for (const double voxel_size : {0.0, 0.05}) {
    absl::StatusOr<PlannedGrid> plan =
        PlanGrid(*cloud, VoxelizeOptions{.voxel_size = voxel_size});
    ASSERT_TRUE(plan.ok()) << plan.status();
    absl::StatusOr<Voxelization> v =
        Voxelize(cloud->points, VoxelizeOptions{.voxel_size = voxel_size});
    ASSERT_TRUE(v.ok()) << v.status();
    EXPECT_EQ(plan->voxels, v->grid.size()) << "voxel size " << voxel_size;
    EXPECT_EQ(plan->voxel_size, v->grid.voxel_size());
    EXPECT_EQ(plan->points, 20000);
    EXPECT_EQ(plan->bytes, GridBytesEstimate(v->grid.size(), 20000));
  }
}

TEST(PlanGrid, AGridOverAGivenBudgetCountsAtTheBudget) {
  absl::StatusOr<PointCloud> cloud =
      SynthesizeShape(SynthOptions{.shape = "torus", .points = 20000});
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  absl::StatusOr<PlannedGrid> plan =
      PlanGrid(*cloud, VoxelizeOptions{.voxel_size = 0.001, .voxel_budget = 1000});
  ASSERT_TRUE(plan.ok()) << plan.status();
  EXPECT_GT(plan->voxels, 1000);
  EXPECT_EQ(plan->bytes, GridBytesEstimate(1000, 20000));
}

TEST(PlanGrid, ACancelDuringFormulaOnesCountIsCancelled) {
  const absl::StatusOr<PointCloud> cloud = SynthesizeShape(SynthOptions{.shape = "sphere", .points = 5000});
  ASSERT_TRUE(cloud.ok());
  CancelToken cancel;
  cancel.Cancel();
  EXPECT_EQ(PlanGrid(*cloud, VoxelizeOptions{}, cancel).status().code(),
            absl::StatusCode::kCancelled);
  // A given voxel size counts nothing, but the point check before it asks the token too.
  EXPECT_EQ(PlanGrid(*cloud, VoxelizeOptions{.voxel_size = 0.1}, cancel).status().code(),
            absl::StatusCode::kCancelled);
  EXPECT_TRUE(PlanGrid(*cloud, VoxelizeOptions{.voxel_size = 0.1}).ok());
}

TEST(PlanGrid, ADegenerateCloudIsInvalidArgument) {
  PointCloud flat;
  for (int i = 0; i < 100; ++i) flat.points.push_back({float(i % 10), float(i / 10), 0});
  EXPECT_EQ(PlanGrid(flat, VoxelizeOptions{}).status().code(),
            absl::StatusCode::kInvalidArgument);
}

TEST(GridBytesEstimate, SaturatesInsteadOfOverflowing) {
  EXPECT_GT(GridBytesEstimate(4'000'000'000'000'000'000, 0), int64_t{1} << 62);
}

// Each stage frees its working sets before the next: the run holds the largest stage's bytes,
// not their sum. The surface's clean-up, which the grid alone decides, counts before the grid.
TEST(GridBytesEstimate, IsTheLargestStageBeforeTheSurfaceOrTheSurfacesGridShare) {
  for (const auto& [voxels, points] : {std::pair<int64_t, int64_t>{1000, 10'000'000},
                                      {2'170'000'000, 10'000'000},
                                      {100'000'000, 0}}) {
    const StageBytes s = EstimateStageBytes(voxels, points, MembraneCounts{});
    EXPECT_EQ(GridBytesEstimate(voxels, points),
              std::max({s.decode, s.voxelize, s.shrink, s.relax, s.surface}));
    EXPECT_LT(GridBytesEstimate(voxels, points), s.decode + s.voxelize + s.shrink + s.relax);
  }
}

TEST(SurfaceBytesEstimate, IsTheLargestStageFromTheSurfaceOnAndGrowsWithTheMembrane) {
  PlannedGrid grid;
  grid.voxels = 100'000'000;
  grid.points = 1'000'000;
  MembraneCounts counts;
  counts.hard_voxels = 10'000;
  counts.frozen_voxels = 20'000;
  counts.soft_voxels = 30'000;
  const StageBytes s = EstimateStageBytes(grid.voxels, grid.points, counts);
  EXPECT_EQ(SurfaceBytesEstimate(grid, counts), std::max(s.surface, s.check));
  MembraneCounts inside = counts;
  inside.inside_soft_voxels = 50'000'000;  // the solid's inside takes no surface
  EXPECT_EQ(SurfaceBytesEstimate(grid, inside), SurfaceBytesEstimate(grid, counts));
  MembraneCounts foam = counts;
  foam.soft_voxels += 1'000'000;
  EXPECT_GT(SurfaceBytesEstimate(grid, foam), SurfaceBytesEstimate(grid, counts));
}

// Peaks measured by bench_memory on the torus (one thread, 11 bits; whole-process bytes,
// tests/bench/2026-12-03-memory.txt): each stage's estimate is at or above its peak, so that a
// gate admitting the estimate admits what the run holds. The shrink holds the grid, 8 work
// planes and the packed anchors; the surface cleans the grid itself up on bit masks, then
// holds the mesh and the fit with the grid freed (kept as runs).
TEST(EstimateStageBytes, CoversThePeaksMeasuredOnTheTorus) {
  struct Measured {
    int64_t voxels, points, membrane_voxels;
    double shrink_mb, relax_mb, surface_mb, check_mb;
  };
  for (const Measured& m : {Measured{70'444'997, 1'000'000, 774'697, 221.3, 108.7, 474.3, 319.7},
                            Measured{197'000'000, 2'000'000, 1'550'309, 553.3, 291.5, 984.1,
                                     602.7}}) {
    MembraneCounts counts;
    counts.soft_voxels = m.membrane_voxels;
    const StageBytes s = EstimateStageBytes(m.voxels, m.points, counts);
    EXPECT_GE(s.shrink, m.shrink_mb * 1e6) << m.points;
    EXPECT_GE(s.relax, m.relax_mb * 1e6) << m.points;
    EXPECT_GE(s.surface, m.surface_mb * 1e6) << m.points;
    EXPECT_GE(s.check, m.check_mb * 1e6) << m.points;
  }
}

// On a 10M-point cloud's grid (2.17e9 voxels, 7.76M boundary voxels) the grid's bytes outweigh
// the membrane's: the surface's share that the grid alone decides (1.35 bytes a voxel) is
// below the shrink's, which decides what is admitted before the grid.
TEST(GridBytesEstimate, TheShrinkDecidesALargeGridNotTheSurface) {
  const StageBytes s = EstimateStageBytes(2'171'747'375, 10'000'000, MembraneCounts{});
  EXPECT_LT(s.surface, s.shrink);
  EXPECT_EQ(GridBytesEstimate(2'171'747'375, 10'000'000), s.shrink);
  // The whole run's peak RSS on that torus (`membrane reconstruct --local`, 2 threads, 12
  // output bits; tests/bench/2026-12-03-memory.txt), which the shrink or the fit reaches.
  EXPECT_GE(s.shrink, int64_t{5'091'684'352});
}

// A plan as PlanGrid makes it, for a grid too large to make a cloud for in a unit test.
PlannedGrid Plan(double voxel_size, int64_t voxels, int64_t points) {
  PlannedGrid plan;
  plan.voxel_size = voxel_size;
  plan.voxels = voxels;
  plan.points = points;
  plan.bytes = GridBytesEstimate(voxels, points);
  return plan;
}

// A 10M-point torus at formula (1) is a 1295^3 grid (2.17e9 voxels): it fits the 3/4 of a
// 24 GB machine that membraned takes by default. Fifty million points at formula (1) are a
// grid of 2.4e10 voxels: more than such a machine has.
TEST(CheckMemoryCeiling, RefusesWhatNoMachineOfThatSizeHolds) {
  constexpr int64_t kMachine = int64_t{24} << 30;
  const PlannedGrid ten_million = Plan(0.0015826, 2'171'747'375, 10'000'000);
  EXPECT_LT(ten_million.bytes, kMachine / 4 * 3);
  EXPECT_TRUE(CheckMemoryCeiling(ten_million, kMachine).ok());
  const PlannedGrid fifty_million = Plan(0.00070775, 24'170'000'000, 50'000'000);
  const absl::Status refused = CheckMemoryCeiling(fifty_million, kMachine);
  EXPECT_EQ(refused.code(), absl::StatusCode::kResourceExhausted);
  EXPECT_THAT(std::string(refused.message()),
              ::testing::AllOf(::testing::HasSubstr("voxel size 0.00070775"),
                               ::testing::HasSubstr("2.42e+10 voxels"),
                               ::testing::HasSubstr("50000000 points"),
                               ::testing::HasSubstr("the ceiling of 25.8 GB")));
  EXPECT_TRUE(CheckMemoryCeiling(fifty_million, 0).ok());  // none
}

// A plan as PlanGrid makes it on a box of 2.6 x 2.6 x 0.6 (a flat torus's), with formula
// (1)'s size for 50M points on such a torus.
PlannedGrid TorusPlan(double voxel_size, int64_t points) {
  PlannedGrid plan;
  plan.bounds = Box3d{{-1.3, -1.3, -0.3}, {1.3, 1.3, 0.3}};
  plan.voxel_size = voxel_size;
  plan.voxels = PlannedVoxelCount(plan.bounds, voxel_size);
  plan.points = points;
  plan.bytes = GridBytesEstimate(plan.voxels, points);
  return plan;
}

bool Fits(const PlannedGrid& plan, double size, int64_t limit, int64_t voxel_budget = 0) {
  const int64_t voxels = PlannedVoxelCount(plan.bounds, size);
  return GridBytesEstimate(voxels, plan.points) <= limit &&
         (voxel_budget <= 0 || voxels <= voxel_budget);
}

// The advice of a refusal: the smallest size whose grid fits, in three significant digits,
// so that the size printed is one that fits and one a hundredth smaller does not.
TEST(SmallestVoxelSizeWithin, IsTheSmallestThreeDigitSizeThatFits) {
  const PlannedGrid plan = TorusPlan(0.00070775, 50'000'000);
  for (const int64_t limit : {int64_t{20} << 30, int64_t{8} << 30, int64_t{4} << 30}) {
    for (const int64_t budget : {int64_t{0}, int64_t{1'000'000'000}}) {
      SCOPED_TRACE(::testing::Message() << "limit " << limit << " voxel budget " << budget);
      const double size = SmallestVoxelSizeWithin(plan, limit, budget);
      ASSERT_GT(size, plan.voxel_size);
      EXPECT_TRUE(Fits(plan, size, limit, budget));
      EXPECT_FALSE(Fits(plan, 0.99 * size, limit, budget));
      const double unit = std::pow(10.0, std::floor(std::log10(size)) - 2);
      EXPECT_NEAR(size / unit, std::round(size / unit), 1e-6) << size;
    }
  }
  // A coarser grid on the same box that fits 20 GB as it is.
  const PlannedGrid ten_million = TorusPlan(0.0015826, 10'000'000);
  EXPECT_EQ(SmallestVoxelSizeWithin(ten_million, int64_t{20} << 30), 0.0015826);
  // No size fits when the points alone are over the limit, nor for a plan with no box.
  EXPECT_EQ(SmallestVoxelSizeWithin(plan, 1000), 0);
  EXPECT_EQ(SmallestVoxelSizeWithin(Plan(0.00070775, 24'170'000'000, 50'000'000), 8LL << 30), 0);
}

TEST(CheckMemoryCeiling, NamesTheVoxelSizeThatFits) {
  const absl::Status refused =
      CheckMemoryCeiling(TorusPlan(0.00070775, 50'000'000), int64_t{24} << 30);
  EXPECT_EQ(refused.code(), absl::StatusCode::kResourceExhausted);
  const double fits = SmallestVoxelSizeWithin(TorusPlan(0.00070775, 50'000'000), 24LL << 30);
  EXPECT_THAT(std::string(refused.message()),
              ::testing::HasSubstr(absl::StrFormat("(voxel size %.3g or larger fits)", fits)));
}

TEST(CheckMemoryCeiling, TheDefaultIsTheMachinesMemory) {
  const PlannedGrid huge = Plan(1e-6, int64_t{1} << 60, 1000);
  const absl::Status refused = CheckMemoryCeiling(huge, -1);
  EXPECT_EQ(refused.code(), absl::StatusCode::kResourceExhausted);
  EXPECT_THAT(std::string(refused.message()), ::testing::HasSubstr("of memory this machine has"));
}

TEST(BytesText, ThreeSignificantDigitsInPowersOfAThousand) {
  EXPECT_EQ(BytesText(512), "512 bytes");
  EXPECT_EQ(BytesText(999), "999 bytes");
  EXPECT_EQ(BytesText(1000), "1 KB");
  EXPECT_EQ(BytesText(38'123'456), "38.1 MB");
  EXPECT_EQ(BytesText(999'600'000), "1 GB");
  EXPECT_EQ(BytesText(2'612'345'678), "2.61 GB");
}

}  // namespace
}  // namespace membrane::testing

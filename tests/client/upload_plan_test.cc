// PlanUpload: the voxel size the server is to use, and the fewest position bits whose Draco
// step is at most 1/kStepsPerVoxel of that voxel.
#include "client/upload_plan.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/engine/voxelization.h"
#include "core/pipeline/memory_estimate.h"
#include "core/geometry/point_cloud.h"
#include "gtest/gtest.h"

namespace membrane::client {
namespace {

// A lattice of n^3 distinct points spaced `spacing` apart from the origin.
PointCloud Lattice(int n, float spacing) {
  PointCloud cloud;
  for (int x = 0; x < n; ++x)
    for (int y = 0; y < n; ++y)
      for (int z = 0; z < n; ++z)
        cloud.points.push_back({x * spacing, y * spacing, z * spacing});
  return cloud;
}

// Draco's quantization step for `bits` over `range`.
double Step(double range, int bits) { return range / (std::ldexp(1.0, bits) - 1); }

// `n` points spread evenly over the unit sphere (a Fibonacci spiral): a clean surface.
PointCloud Sphere(int n) {
  PointCloud cloud;
  const double golden = M_PI * (3 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1 - (i + 0.5) * 2 / n;
    const double r = std::sqrt(1 - z * z);
    cloud.points.push_back({static_cast<float>(r * std::cos(golden * i)),
                            static_cast<float>(r * std::sin(golden * i)),
                            static_cast<float>(z)});
  }
  return cloud;
}

TEST(UploadPlan, DefaultVoxelOfASurfaceIsFormulaOnesWithNoNote) {
  const PointCloud cloud = Sphere(8000);
  const UploadPlan plan = PlanUpload(cloud, 0);
  const absl::StatusOr<Box3d> bounds = CheckedBounds(cloud.points);
  ASSERT_TRUE(bounds.ok());
  EXPECT_NEAR(plan.voxel_size, EstimateVoxelSize(*bounds, 8000), 1e-9);
  EXPECT_FALSE(plan.noise_note.has_value()) << *plan.noise_note;
  // 2 / 0.055 * 8 = 291 steps: the default 11 bits (2047 steps) are fine enough.
  EXPECT_EQ(plan.bits, kDefaultUploadBits);
}

TEST(UploadPlan, TheSamePlanOnAnyThreadCount) {
  // Enough points for the distinct count to split, a third of them repeated (a scanner's
  // overlapping views): formula (1) counts each once.
  PointCloud cloud = Sphere(300000);
  for (int i = 0; i < 100000; ++i) cloud.points.push_back(cloud.points[3 * i]);
  const UploadPlan alone = PlanUpload(cloud, 0, 1);
  ASSERT_TRUE(alone.voxel_plan.has_value());
  const absl::StatusOr<Box3d> bounds = CheckedBounds(cloud.points);
  ASSERT_TRUE(bounds.ok());
  EXPECT_NEAR(alone.voxel_plan->formula_voxel_size, EstimateVoxelSize(*bounds, 300000), 1e-12);
  for (int threads : {2, 3}) {
    const UploadPlan plan = PlanUpload(cloud, 0, threads);
    EXPECT_EQ(plan.voxel_size, alone.voxel_size) << threads;
    EXPECT_EQ(plan.bits, alone.bits) << threads;
    ASSERT_TRUE(plan.voxel_plan.has_value());
    EXPECT_EQ(plan.voxel_plan->formula_voxel_size, alone.voxel_plan->formula_voxel_size);
    EXPECT_EQ(plan.voxel_plan->point_noise, alone.voxel_plan->point_noise);
  }
}

// A lattice fills a volume, which reads as noise: the default voxel is PlanGrid's, coarser than
// formula (1)'s, and the plan carries the note that the server, given that size, cannot make.
TEST(UploadPlan, DefaultVoxelIsThePipelinesWithItsNoiseNote) {
  const PointCloud cloud = Lattice(20, 1.0f);  // side 19, 8000 points
  const UploadPlan plan = PlanUpload(cloud, 0);
  const absl::StatusOr<PlannedGrid> grid = PlanGrid(cloud, VoxelizeOptions{});
  ASSERT_TRUE(grid.ok()) << grid.status();
  EXPECT_EQ(plan.voxel_size, grid->voxel_size);
  EXPECT_GT(plan.voxel_size, grid->formula_voxel_size);
  ASSERT_TRUE(plan.noise_note.has_value());
  EXPECT_NE(plan.noise_note->find("scatter across their surface"), std::string::npos);
  // How it was chosen goes with it (Parameters.voxel_plan), for the server to run as --local.
  ASSERT_TRUE(plan.voxel_plan.has_value());
  EXPECT_EQ(plan.voxel_plan->formula_voxel_size, grid->formula_voxel_size);
  EXPECT_EQ(plan.voxel_plan->point_noise, grid->noise.sigma);
}

// A default voxel carries its plan even where it is formula (1)'s; a given one carries none.
TEST(UploadPlan, VoxelPlanOnlyForTheDefaultVoxel) {
  const PointCloud cloud = Sphere(8000);
  const UploadPlan chosen = PlanUpload(cloud, 0);
  ASSERT_TRUE(chosen.voxel_plan.has_value());
  EXPECT_EQ(chosen.voxel_plan->formula_voxel_size, chosen.voxel_size);
  EXPECT_FALSE(PlanUpload(cloud, 0.1).voxel_plan.has_value());
}

// The server plans its grid on the box the client read (Parameters.grid_box): the cloud's own.
TEST(UploadPlan, BoxIsTheCloudsOwnAndNoneForADegenerateCloud) {
  const PointCloud cloud = Sphere(8000);
  const absl::StatusOr<Box3d> bounds = CheckedBounds(cloud.points);
  ASSERT_TRUE(bounds.ok());
  for (const double voxel : {0.0, 0.1}) {
    const UploadPlan plan = PlanUpload(cloud, voxel);
    ASSERT_TRUE(plan.box.has_value());
    EXPECT_EQ(plan.box->min, bounds->min);
    EXPECT_EQ(plan.box->max, bounds->max);
  }
  PointCloud flat;
  for (int i = 0; i < 100; ++i) flat.points.push_back({static_cast<float>(i % 10), 0, i / 10.0f});
  EXPECT_FALSE(PlanUpload(flat, 0).box.has_value());
}

TEST(UploadPlan, KeepsTheRequestedVoxel) {
  EXPECT_DOUBLE_EQ(PlanUpload(Lattice(10, 1.0f), 0.25).voxel_size, 0.25);
}

TEST(UploadPlan, StepIsAtMostAnEighthOfTheVoxelWithTheFewestBits) {
  const PointCloud cloud = Lattice(10, 1.0f);  // side 9
  const double range = 9;
  int previous_bits = 0;
  // Ever finer voxels, from 3 model units down to 3e-6.
  for (double voxel = 3; voxel > 3e-6; voxel /= 3) {
    const UploadPlan plan = PlanUpload(cloud, voxel);
    ASSERT_DOUBLE_EQ(plan.voxel_size, voxel);
    EXPECT_GE(plan.bits, kDefaultUploadBits) << voxel;
    EXPECT_LE(Step(range, plan.bits), voxel / kStepsPerVoxel) << voxel;
    if (plan.bits > kDefaultUploadBits) {
      // One bit fewer would be too coarse.
      EXPECT_GT(Step(range, plan.bits - 1), voxel / kStepsPerVoxel) << voxel;
    }
    EXPECT_GE(plan.bits, previous_bits) << voxel;  // finer voxels never take fewer bits
    previous_bits = plan.bits;
  }
  EXPECT_GT(previous_bits, kDefaultUploadBits);
}

TEST(UploadPlan, TheLargestSideSetsTheBits) {
  // A slab 1000 x 10 x 10 with a voxel of 0.05: 1000 / 0.05 * 8 = 160000 steps, 18 bits
  // (2^17 - 1 = 131071 is too few); the short sides alone would need 11.
  PointCloud cloud;
  for (int i = 0; i <= 100; ++i) {
    cloud.points.push_back({i * 10.0f, 0, 0});
    cloud.points.push_back({i * 10.0f, 10, 10});
    cloud.points.push_back({i * 10.0f, 0, 10});
  }
  EXPECT_EQ(PlanUpload(cloud, 0.05).bits, 18);
}

TEST(UploadPlan, BitsStopAtThirty) {
  const UploadPlan plan = PlanUpload(Lattice(10, 1.0f), 1e-9);
  EXPECT_EQ(plan.bits, 30);
}

TEST(UploadPlan, ADegenerateCloudLeavesTheVoxelToTheServer) {
  const UploadPlan empty = PlanUpload(PointCloud{}, 0);
  EXPECT_EQ(empty.voxel_size, 0);
  EXPECT_EQ(empty.bits, kDefaultUploadBits);

  PointCloud flat;  // every point in the plane z = 0
  for (int x = 0; x < 10; ++x)
    for (int y = 0; y < 10; ++y) flat.points.push_back({float(x), float(y), 0});
  const UploadPlan coplanar = PlanUpload(flat, 0);
  EXPECT_EQ(coplanar.voxel_size, 0);
  EXPECT_EQ(coplanar.bits, kDefaultUploadBits);
}

}  // namespace
}  // namespace membrane::client

// A dense scan's interior guard: where the points' noise chose the voxel (VoxelRaisedForNoise),
// the pipeline guards the interior on grids far narrower than InteriorGuardOptions'
// min_coarse_axis lets it (DenseScanGuard); the same size given keeps the guard's own rule.
#include <gtest/gtest.h>

#include <optional>
#include <vector>

#include "core/engine/interior_guard.h"
#include "core/engine/shrink_options.h"
#include "core/engine/point_noise.h"
#include "core/pipeline/reconstruction_options.h"
#include "core/synth/synthesize.h"
#include "tests/support/in_memory_run.h"
#include "tests/support/shrink_fixture.h"

namespace membrane::testing {
namespace {

// A unit sphere of 400k points with range noise of 0.002 (0.26 of formula (1)'s voxel) and
// two unscanned patches: the default voxel is raised to about 0.013, a grid about 160 voxels
// wide, under the 4 x 96 of the guard's own rule.
PointCloud DenseNoisySphere() {
  absl::StatusOr<PointCloud> cloud = SynthesizeShape(SynthOptions{
      .shape = "sphere", .points = 400000, .holes = 2, .noise = 0.002, .seed = 3});
  EXPECT_TRUE(cloud.ok()) << cloud.status();
  return cloud.value_or(PointCloud{});
}

ReconstructionReport Reconstruct(const PointCloud& cloud, double voxel_size,
                                 std::optional<VoxelPlanNote> plan = std::nullopt) {
  ReconstructionOptions options;
  options.voxelize.voxel_size = voxel_size;
  options.voxel_plan = plan;
  options.surface = SurfaceKind::kCuberille;
  options.threads = 2;
  absl::StatusOr<ReconstructionReport> r = ReconstructInMemory(cloud, options);
  EXPECT_TRUE(r.ok()) << r.status();
  return r.value_or(ReconstructionReport{});
}

TEST(DenseScanGuard, LowersTheWidthAndTheOpenRaysAndGuardsOnePieceOnly) {
  const InteriorGuardOptions given;
  const InteriorGuardOptions dense = DenseScanGuard(given);
  EXPECT_EQ(dense.min_coarse_axis, kDenseScanMinCoarseAxis);
  EXPECT_EQ(dense.band_release_below, given.band_release_below);
  EXPECT_TRUE(dense.one_piece_only);
  EXPECT_EQ(dense.enabled, given.enabled);
  EXPECT_EQ(dense.factor, given.factor);
  EXPECT_EQ(dense.max_open_rays, kDenseScanMaxOpenRays);
  // Never a wider threshold than asked for.
  InteriorGuardOptions narrow;
  narrow.min_coarse_axis = 8;
  narrow.band_release_below = 0;
  EXPECT_EQ(DenseScanGuard(narrow).min_coarse_axis, 8);
  EXPECT_EQ(DenseScanGuard(narrow).band_release_below, 0);
}

TEST(DenseScanGuard, GuardsANoiseRaisedGridAndNotTheSameSizeGiven) {
  const PointCloud cloud = DenseNoisySphere();
  const ReconstructionReport raised = Reconstruct(cloud, 0);
  ASSERT_TRUE(VoxelRaisedForNoise(raised.formula_voxel_size, raised.voxel_size))
      << raised.voxel_size << " against formula (1)'s " << raised.formula_voxel_size;
  ASSERT_LT(raised.data_grid[0], 4 * InteriorGuardOptions{}.min_coarse_axis);
  EXPECT_EQ(raised.interior_guard.levels, 1);
  EXPECT_GT(raised.interior_guard.frozen_voxels, 0);
  EXPECT_EQ(raised.membrane.shells, 1);
  EXPECT_EQ(raised.membrane.genus, std::vector<int>{0});
  EXPECT_TRUE(raised.mesh.closed);
  EXPECT_EQ(raised.mesh.nonmanifold_vertices, 0);
  // The guarded shrink's own contract: the membrane invariants, each shell's membrane
  // 6-connected among them, whatever hard voxels the band's late release leaves hanging.
  ShrinkOptions guarded;
  guarded.interior_guard = DenseScanGuard(guarded.interior_guard);
  guarded.threads = 2;
  const absl::StatusOr<ShrinkRun> shrunk = ShrinkCloud(cloud, 0, guarded, raised.voxel_size);
  ASSERT_TRUE(shrunk.ok()) << shrunk.status();
  EXPECT_GT(shrunk->result.interior_guard.frozen_voxels, 0);
  EXPECT_TRUE(shrunk->invariants.ok()) << shrunk->Describe();

  const ReconstructionReport given = Reconstruct(cloud, raised.voxel_size);
  EXPECT_EQ(given.data_grid, raised.data_grid);
  EXPECT_EQ(given.formula_voxel_size, 0);
  EXPECT_EQ(given.interior_guard.levels, 0);
  EXPECT_EQ(given.interior_guard.frozen_voxels, 0);

  // The size given with how it was planned (a server's run on the client's upload): reported
  // and guarded as the run that planned it.
  const ReconstructionReport planned = Reconstruct(
      cloud, raised.voxel_size, VoxelPlanNote{raised.formula_voxel_size, raised.point_noise});
  EXPECT_EQ(planned.formula_voxel_size, raised.formula_voxel_size);
  EXPECT_EQ(planned.point_noise, raised.point_noise);
  EXPECT_EQ(planned.interior_guard.frozen_voxels, raised.interior_guard.frozen_voxels);
  EXPECT_EQ(planned.membrane.genus, raised.membrane.genus);
  EXPECT_EQ(planned.mesh.faces, raised.mesh.faces);
}

}  // namespace
}  // namespace membrane::testing

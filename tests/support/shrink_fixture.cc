#include "tests/support/shrink_fixture.h"

#include <cstdlib>
#include <iostream>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "core/engine/membrane_invariants.h"
#include "core/synth/synthesize.h"

namespace membrane::testing {

std::string ShrinkRun::Describe() const {
  const auto& d = voxels.grid.dims();
  return absl::StrCat("shells=", topology.shells, " genus=[", absl::StrJoin(topology.genus, ","),
                      "] grid=", d[0], "x", d[1], "x", d[2], " hard=", voxels.hard_voxels,
                      " inside_hard=", result.post_process.inside_hard_after,
                      " invariants=", invariants.ToString());
}

absl::StatusOr<ShrinkRun> ShrinkCloud(const PointCloud& cloud, double factor,
                                      const ShrinkOptions& options, double voxel_size) {
  absl::StatusOr<Box3d> bounds = CheckedBounds(cloud.points);
  if (!bounds.ok()) return bounds.status();
  VoxelizeOptions vo;
  vo.voxel_size = voxel_size > 0
                      ? voxel_size
                      : factor * EstimateVoxelSize(*bounds, static_cast<int64_t>(cloud.points.size()));
  absl::StatusOr<Voxelization> voxels = Voxelize(cloud.points, vo);
  if (!voxels.ok()) return voxels.status();
  ShrinkRun run;
  run.voxels = std::move(*voxels);
  absl::StatusOr<ShrinkResult> result =
      ShrinkMembrane(run.voxels.grid, cloud.points, options, {}, CancelToken::Never());
  if (!result.ok()) return result.status();
  run.result = std::move(*result);
  run.topology = ComputeVoxelTopology(run.voxels.grid);
  InvariantOptions io;
  // The piece separation may cut hard voxels where two pieces touch; every other one stays.
  io.expected_hard_voxels = run.voxels.hard_voxels - run.result.separation.hard_cut_voxels;
  run.invariants = CheckMembraneInvariants(run.voxels.grid, io);
  return run;
}

PointCloud SynthCloud(const std::string& shape, int64_t points, double density_ratio,
                      uint64_t seed) {
  SynthOptions o;
  o.shape = shape;
  o.points = points;
  o.density_ratio = density_ratio;
  o.seed = seed;
  absl::StatusOr<PointCloud> cloud = SynthesizeShape(o);
  if (!cloud.ok()) {
    std::cerr << "synth " << shape << ": " << cloud.status() << "\n";
    std::abort();
  }
  return *std::move(cloud);
}

}  // namespace membrane::testing

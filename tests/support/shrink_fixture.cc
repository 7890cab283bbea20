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

int ShrinkRun::RetryFromPlate() const {
  const int g = result.handle_retry.from_generation;
  return g > 0 ? result.generations[g - 1].plate_size : 0;
}

std::string ShrinkRun::DescribeRetry() const {
  const HandleRetry& r = result.handle_retry;
  return absl::StrCat(Describe(), "; retry from generation ", r.from_generation, " (plate ",
                      RetryFromPlate(), "): genus ", r.genus_before, " -> ", r.genus_after, ", ",
                      r.kept ? "kept" : "not kept");
}

std::string RetryMissOfWebs(const ShrinkRun& run, int plate) {
  std::vector<std::string> misses;
  if (!run.invariants.ok()) misses.push_back("invariants broken");
  if (!run.result.handle_retry.kept) misses.push_back("retry not kept");
  if (run.RetryFromPlate() != plate) misses.push_back(absl::StrCat("retry not from plate ", plate));
  if (TotalGenus(run.topology) > 0) misses.push_back("handles left");
  if (misses.empty()) return "";
  return absl::StrCat(run.DescribeRetry(), ": ", absl::StrJoin(misses, ", "));
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

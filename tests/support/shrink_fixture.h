// Helpers shared by the engine's tests: voxelize a cloud at a multiple of the formula-(1)
// voxel size, shrink it, and report what the tests assert on.
#ifndef MEMBRANE_TESTS_SUPPORT_SHRINK_FIXTURE_H_
#define MEMBRANE_TESTS_SUPPORT_SHRINK_FIXTURE_H_

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "core/engine/membrane_shrinker.h"
#include "core/engine/voxel_topology.h"
#include "core/engine/voxelization.h"
#include "core/geometry/point_cloud.h"

namespace membrane::testing {

struct ShrinkRun {
  Voxelization voxels;     // the final DMS in voxels.grid
  ShrinkResult result;
  VoxelTopology topology;
  absl::Status invariants;
  std::string Describe() const;  // "shells=1 genus=[0] grid=..x..x.. invariants=OK"
  // The plate of the generation the handle retry started from (0: none qualified).
  int RetryFromPlate() const;
  // Describe(), then "; retry from generation G (plate n): genus a -> b, kept" (or "not kept").
  std::string DescribeRetry() const;
};

// Voxelizes `points` at `factor` x the formula-(1) voxel size (or exactly `voxel_size` when it
// is > 0), shrinks with `options`, and computes topology and invariants.
absl::StatusOr<ShrinkRun> ShrinkCloud(const PointCloud& cloud, double factor,
                                      const ShrinkOptions& options = {}, double voxel_size = 0);

// Empty when `run`'s invariants hold, its handle retry started at the generation of plate
// `plate` and was kept, and no shell has a handle; else DescribeRetry() and what differs.
std::string RetryMissOfWebs(const ShrinkRun& run, int plate);

// A cloud of `shape` from membrane_synth; aborts the test binary on a bad shape.
PointCloud SynthCloud(const std::string& shape, int64_t points, double density_ratio = 1.0,
                      uint64_t seed = 7);

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_SUPPORT_SHRINK_FIXTURE_H_

#include "core/engine/point_density.h"

#include <algorithm>
#include <cmath>

#include "core/base/parallel_tasks.h"

namespace membrane {
namespace {

// Points per task of the two passes that deal the points into slabs: a count per block and
// slab is all the bookkeeping, and the blocks, not the threads, fix where each point goes.
constexpr int64_t kBlockPoints = int64_t{1} << 16;
// Slabs of z planes sorted apart: enough to share among the threads and to keep each sort in
// a few MB at 10M points.
constexpr int kMaxSlabs = 256;

}  // namespace

std::array<int, 3> DataDims(const Box3d& bounds, double voxel_size) {
  const auto extent = bounds.Extent();
  std::array<int, 3> dims;
  for (int d = 0; d < 3; ++d) dims[d] = static_cast<int>(std::floor(extent[d] / voxel_size)) + 1;
  return dims;
}

std::vector<int64_t> SortedPointVoxels(absl::Span<const Point3f> points, const Box3d& bounds,
                                       double voxel_size, const std::array<int, 3>& dims,
                                       int threads, const CancelToken& cancel) {
  const auto n = static_cast<int64_t>(points.size());
  const int64_t plane = int64_t{dims[0]} * dims[1];
  const int slabs = std::clamp(dims[2], 1, kMaxSlabs);
  auto voxel_of = [&](const Point3f& p) {
    int64_t c[3];
    for (int d = 0; d < 3; ++d) c[d] = DataVoxelAlong(p[d], bounds.min[d], voxel_size, dims[d]);
    return c[0] + dims[0] * (c[1] + int64_t{dims[1]} * c[2]);
  };
  // Increasing with the voxel index, so that the slabs in order, each sorted, are the list.
  auto slab_of = [&](int64_t voxel) { return static_cast<int>(voxel / plane * slabs / dims[2]); };
  const int64_t blocks = (n + kBlockPoints - 1) / kBlockPoints;
  auto block_end = [&](int64_t b) { return std::min(n, (b + 1) * kBlockPoints); };
  // Per block and slab: the block's points in the slab, then where the next of them goes.
  std::vector<int64_t> at(blocks * slabs, 0);
  TaskCancel stop(cancel, threads, 1);
  RunTasks(threads, blocks, [&](int worker, int64_t b) {
    if (stop.Poll(worker)) return;
    int64_t* count = at.data() + b * slabs;
    for (int64_t i = b * kBlockPoints; i < block_end(b); ++i) ++count[slab_of(voxel_of(points[i]))];
  });
  if (stop.fired()) return {};
  std::vector<int64_t> slab_start(slabs + 1, 0);
  int64_t placed = 0;
  for (int s = 0; s < slabs; ++s) {
    slab_start[s] = placed;
    for (int64_t b = 0; b < blocks; ++b) {
      const int64_t count = at[b * slabs + s];
      at[b * slabs + s] = placed;
      placed += count;
    }
  }
  slab_start[slabs] = placed;
  std::vector<int64_t> sorted(n);
  RunTasks(threads, blocks, [&](int worker, int64_t b) {
    if (stop.Poll(worker)) return;
    int64_t* next = at.data() + b * slabs;
    for (int64_t i = b * kBlockPoints; i < block_end(b); ++i) {
      const int64_t voxel = voxel_of(points[i]);
      sorted[next[slab_of(voxel)]++] = voxel;
    }
  });
  RunTasks(threads, slabs, [&](int worker, int64_t s) {
    if (stop.Poll(worker)) return;
    std::sort(sorted.begin() + slab_start[s], sorted.begin() + slab_start[s + 1]);
  });
  return sorted;
}

PointDensity MeasurePointDensity(absl::Span<const Point3f> points, const Box3d& bounds,
                                 double voxel_size, int threads) {
  return ForEachOccupiedVoxel(
      SortedPointVoxels(points, bounds, voxel_size, DataDims(bounds, voxel_size), threads),
      [](int64_t, int64_t) {});
}

}  // namespace membrane

#include "core/engine/point_density.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <vector>

#include "core/base/parallel_tasks.h"

namespace membrane {
namespace {

// Points per task of the two passes that deal the points into slabs: a count per block and
// slab is all the bookkeeping, and the blocks, not the threads, fix where each point goes.
constexpr int64_t kBlockPoints = int64_t{1} << 16;
// Slabs of z planes sorted apart: enough to share among the threads and to keep each sort in
// a few MB at 10M points.
constexpr int kMaxSlabs = 256;
// Below this many voxels a slab is sorted by comparisons: the radix passes' counts would cost
// more than the sort.
constexpr int64_t kMinRadixItems = 256;

// Sorts the n voxel indices from `a` on ascending, by least significant digit first over their
// span (max - min): at most 12 bits a digit, a pass of counting and placing each (two for a
// span of up to 2^24 voxels, such as a slab of five 1295^2 planes at 10M points). The
// comparisons of a sort grow with the log of the slab's size: at 10M points std::sort took a
// quarter of the voxelization's CPU. `scratch` is resized to n.
void SortVoxels(int64_t* a, int64_t n, std::vector<int64_t>& scratch) {
  if (n < kMinRadixItems) {
    std::sort(a, a + n);
    return;
  }
  const auto [lo_it, hi_it] = std::minmax_element(a, a + n);
  const int64_t lo = *lo_it;
  const auto span = static_cast<uint64_t>(*hi_it - lo);
  if (span == 0) return;
  const int bits = std::bit_width(span);
  const int passes = (bits + 11) / 12;
  const int width = (bits + passes - 1) / passes;
  const uint64_t mask = (uint64_t{1} << width) - 1;
  scratch.resize(static_cast<size_t>(n));
  std::vector<int64_t> count(static_cast<size_t>(mask) + 2);
  int64_t* from = a;
  int64_t* to = scratch.data();
  for (int pass = 0; pass < passes; ++pass) {
    const int shift = pass * width;
    auto digit = [&](int64_t v) { return (static_cast<uint64_t>(v - lo) >> shift) & mask; };
    std::fill(count.begin(), count.end(), 0);
    for (int64_t i = 0; i < n; ++i) ++count[digit(from[i]) + 1];
    for (size_t d = 1; d < count.size(); ++d) count[d] += count[d - 1];
    for (int64_t i = 0; i < n; ++i) to[count[digit(from[i])]++] = from[i];
    std::swap(from, to);
  }
  if (from != a) std::copy(from, from + n, a);
}

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
  std::vector<std::vector<int64_t>> scratch(static_cast<size_t>(std::max(threads, 1)));
  RunTasks(threads, slabs, [&](int worker, int64_t s) {
    if (stop.Poll(worker)) return;
    SortVoxels(sorted.data() + slab_start[s], slab_start[s + 1] - slab_start[s],
               scratch[static_cast<size_t>(worker)]);
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

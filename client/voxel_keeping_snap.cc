#include "client/voxel_keeping_snap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/base/parallel_tasks.h"
#include "core/engine/point_density.h"
#include "core/pipeline/grid_box.h"

namespace membrane::client {

namespace {

// Fewer points than this are snapped on the calling thread: a thread's start costs more.
constexpr int64_t kMinSplitPoints = 1 << 16;

}  // namespace

std::optional<VoxelKeepingSnap> SnapKeepingVoxels(std::vector<Point3f>& points, const Box3d& box,
                                                  double voxel_size, int bits, int threads) {
  if (bits <= 0) return std::nullopt;
  VoxelKeepingSnap snap;
  snap.grid = GridOverBox(bits, box.min, box.max, 0.0);
  if (!(snap.grid.step() <= voxel_size / kGridBoxStepsPerVoxel)) return std::nullopt;
  const std::array<int, 3> dims = DataDims(box, voxel_size);
  const PositionGrid& grid = snap.grid;
  const int32_t max_q = grid.max_quantized();
  const float inverse_delta = grid.InverseDelta();
  // Draco's dequantization, q * delta + origin in float (PositionGrid::Snap).
  const float delta = grid.box.range / static_cast<float>(max_q);
  // Each point moves alone: ranges of them on the threads, their counts and maxima joined
  // after (a sum and a maximum, the same for any split).
  const TaskRanges ranges = TaskRanges::Split(static_cast<int64_t>(points.size()), threads,
                                              /*per_thread=*/1, kMinSplitPoints);
  std::vector<int64_t> moved(ranges.tasks, 0);
  std::vector<double> max_error(ranges.tasks, 0);
  RunTasks(threads, ranges.tasks, [&](int, int64_t t) {
    for (int64_t i = ranges.begin(t); i < ranges.end(t); ++i) {
      Point3f& p = points[i];
      for (int c = 0; c < 3; ++c) {
        const float v = grid.Scaled(p[c], c, inverse_delta);
        int32_t q = static_cast<int32_t>(
            std::floor((v > 0 ? std::min(v, static_cast<float>(max_q)) : 0.0f) + 0.5f));
        const auto node = [&](int32_t k) {
          return static_cast<float>(k) * delta + grid.box.origin[c];
        };
        const int64_t voxel = DataVoxelAlong(p[c], box.min[c], voxel_size, dims[c]);
        float out = node(q);
        const int64_t landed = DataVoxelAlong(out, box.min[c], voxel_size, dims[c]);
        if (landed != voxel) {
          // A step is at most 1/8 voxel: the node back towards the point is inside its voxel.
          q = std::clamp(q + (landed > voxel ? -1 : 1), 0, max_q);
          out = node(q);
          ++moved[t];
        }
        max_error[t] = std::max(max_error[t], std::fabs(double{out} - p[c]));
        p[c] = out;
      }
    }
  });
  for (int64_t t = 0; t < ranges.tasks; ++t) {
    snap.moved_coordinates += moved[t];
    snap.max_error = std::max(snap.max_error, max_error[t]);
  }
  return snap;
}

}  // namespace membrane::client

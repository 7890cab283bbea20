#include "client/voxel_keeping_snap.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/engine/point_density.h"
#include "core/pipeline/grid_box.h"

namespace membrane::client {

std::optional<VoxelKeepingSnap> SnapKeepingVoxels(std::vector<Point3f>& points, const Box3d& box,
                                                  double voxel_size, int bits) {
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
  for (Point3f& p : points) {
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
        ++snap.moved_coordinates;
      }
      snap.max_error = std::max(snap.max_error, std::fabs(double{out} - p[c]));
      p[c] = out;
    }
  }
  return snap;
}

}  // namespace membrane::client

#include "core/mesh/output_grid.h"

#include <algorithm>
#include <array>

namespace membrane {

PositionGrid OutputGrid(const VoxelGrid& membrane, int bits) {
  const double side =
      membrane.voxel_size() * std::max({membrane.dim(0), membrane.dim(1), membrane.dim(2)});
  const std::array<double, 3>& low = membrane.origin();
  // Widened a little, so that float rounding cannot put the grid's last voxel outside it.
  return GridOverBox(bits, low, {low[0] + side, low[1] + side, low[2] + side}, 1e-6);
}

int OutputBitsForVoxel(const VoxelGrid& membrane, int bits) {
  if (bits <= 0) return bits;
  const double largest_step = kMaxOutputStepVoxels * membrane.voxel_size();
  while (bits < 30 && OutputGrid(membrane, bits).step() > largest_step) ++bits;
  return bits;
}

}  // namespace membrane

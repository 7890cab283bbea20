#include "core/mesh/output_grid.h"

#include <algorithm>

namespace membrane {

PositionGrid OutputGrid(const VoxelGrid& membrane, int bits) {
  PositionGrid grid;
  grid.bits = bits;
  const double side =
      membrane.voxel_size() * std::max({membrane.dim(0), membrane.dim(1), membrane.dim(2)});
  // Rounded outward, so that the grid the surface is snapped to is the grid the file is
  // decoded on and holds every voxel.
  double far_side = 0;
  for (int axis = 0; axis < 3; ++axis) {
    grid.box.origin[axis] = DecimalSafeBound(membrane.origin()[axis], /*lower=*/true);
    far_side = std::max(far_side, membrane.origin()[axis] + side - grid.box.origin[axis]);
  }
  grid.box.range = DecimalSafeBound(far_side * (1 + 1e-6), /*lower=*/false);
  return grid;
}

}  // namespace membrane

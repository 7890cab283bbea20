// A box of a grid's voxels, as written by a chain or read by a local snapshot.
#ifndef MEMBRANE_CORE_ENGINE_VOXEL_BOX_H_
#define MEMBRANE_CORE_ENGINE_VOXEL_BOX_H_

#include <algorithm>

#include "core/engine/voxel_grid.h"

namespace membrane {

// Voxels [lo, hi] (inclusive) of a grid; empty when hi < lo along some axis.
struct VoxelBox {
  Coord lo{0, 0, 0};
  Coord hi{-1, -1, -1};
  bool empty() const { return hi.x < lo.x || hi.y < lo.y || hi.z < lo.z; }
  // Grows the box to hold `c`.
  void Add(const Coord& c) {
    if (empty()) {
      lo = hi = c;
      return;
    }
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], c[d]);
      hi[d] = std::max(hi[d], c[d]);
    }
  }
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_VOXEL_BOX_H_

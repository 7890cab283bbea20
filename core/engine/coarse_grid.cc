#include "core/engine/coarse_grid.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>

#include "core/base/parallel_tasks.h"
#include "core/engine/voxelization.h"

namespace membrane {

VoxelGrid CoarseGrid(const VoxelGrid& fine, int k, int threads) {
  constexpr int kPad = VoxelGrid::kPadding;
  std::array<int, 3> dims;
  std::array<double, 3> origin;
  const double l = fine.voxel_size();
  for (int d = 0; d < 3; ++d) {
    dims[d] = (fine.dim(d) - 2 * kPad + k - 1) / k + 2 * kPad;
    origin[d] = fine.origin()[d] + kPad * l - kPad * k * l;
  }
  VoxelGrid coarse(dims, origin, k * l, VoxelGrid::Unset{});
  // Before the first generation a data voxel's state has bit 1 set exactly when it is hard and
  // bit 2 when the interior guard froze it: eight voxels at a time are skipped when none has.
  constexpr uint64_t kHardOrFrozenBits = 0x0606060606060606ull;
  const int64_t row = fine.dim(0) - 2 * kPad;
  RunTasks(threads, dims[2], [&](int, int64_t task) {
    const int cz = static_cast<int>(task);
    WriteInitialPlane(cz, coarse);
    if (cz < kPad || cz >= dims[2] - kPad) return;
    const int z1 = std::min(kPad + (cz - kPad + 1) * k, fine.dim(2) - kPad);
    for (int z = kPad + (cz - kPad) * k; z < z1; ++z) {
      for (int y = kPad; y < fine.dim(1) - kPad; ++y) {
        const VoxelState* states = fine.states().data() + fine.Index(kPad, y, z);
        for (int64_t x = 0; x < row; x += 8) {
          if (x + 8 <= row) {
            uint64_t word;
            std::memcpy(&word, states + x, 8);
            if ((word & kHardOrFrozenBits) == 0) continue;
          }
          for (int64_t i = x; i < std::min(row, x + 8); ++i) {
            const bool hard = IsHard(states[i]);
            if (!hard && !IsFrozen(states[i])) continue;
            const int64_t c = coarse.Index(static_cast<int>(i / k) + kPad, (y - kPad) / k + kPad,
                                           cz);
            const VoxelState now = coarse.at(c);
            if (IsHard(now)) continue;
            const bool boundary = IsBoundary(now);
            if (hard) {
              coarse.set(c, boundary ? kBoundaryHard : kInsideHard);
            } else {
              coarse.set(c, boundary ? kBoundaryFrozen : kInsideFrozen);
            }
          }
        }
      }
    }
  });
  return coarse;
}

}  // namespace membrane

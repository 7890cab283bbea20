#include "core/engine/plug_wall_core.h"

#include "core/engine/voxel_state.h"

namespace membrane {

bool PlugInsideWallCore(const VoxelGrid& grid, int64_t mid, const Coord& dir, int ring_radius,
                        int depth) {
  const auto st = grid.strides();
  const VoxelState* s = grid.states().data();
  int met = 0;
  for (int k = 0; k < 27; ++k) {
    const Coord& e = kBlockSteps[k];
    if (k == kBlockCentre || e.x * dir.x + e.y * dir.y + e.z * dir.z != 0) continue;
    const int64_t step = e.x * st[0] + e.y * st[1] + e.z * st[2];
    Coord c = grid.CoordOf(mid);
    int64_t q = mid;
    bool hard = false;
    for (int t = 1; t <= ring_radius; ++t) {
      q += step;
      c = {c.x + e.x, c.y + e.y, c.z + e.z};
      if (!grid.Contains(c)) break;
      if (IsHard(s[q])) {
        hard = true;
        break;
      }
      if (IsInside(s[q])) break;
    }
    if (!hard) continue;
    ++met;
    // Past the hard run: the outside within `depth` non-hard voxels, or the solid.
    bool outside = false;
    for (int past = 0; past < depth;) {
      q += step;
      c = {c.x + e.x, c.y + e.y, c.z + e.z};
      if (!grid.Contains(c)) break;
      if (IsOutside(s[q])) {
        outside = true;
        break;
      }
      if (!IsHard(s[q])) ++past;
    }
    if (!outside) return false;
  }
  return met > 0;
}

}  // namespace membrane

#include "core/engine/plug_wall_core.h"

#include <algorithm>

#include "core/engine/voxel_state.h"

namespace membrane {
namespace {

// Walks the lattice rays from `mid` perpendicular to `dir` as the hole tests do (at most
// `ring_radius` voxels through non-hard voxels, stopped by an inside voxel or the array's
// end) and calls met(step, index, coord, t) for the first hard voxel of each ray that meets
// one, t steps from `mid`, until it returns false; returns how many rays met data, -1 when
// stopped.
template <typename F>
int ForEachDataMetAcross(const VoxelGrid& grid, int64_t mid, const Coord& dir, int ring_radius,
                         F met) {
  const auto st = grid.strides();
  const VoxelState* s = grid.states().data();
  int count = 0;
  for (int k = 0; k < 27; ++k) {
    const Coord& e = kBlockSteps[k];
    if (k == kBlockCentre || e.x * dir.x + e.y * dir.y + e.z * dir.z != 0) continue;
    const int64_t step = e.x * st[0] + e.y * st[1] + e.z * st[2];
    Coord c = grid.CoordOf(mid);
    int64_t q = mid;
    for (int t = 1; t <= ring_radius; ++t) {
      q += step;
      c = {c.x + e.x, c.y + e.y, c.z + e.z};
      if (!grid.Contains(c)) break;
      if (IsHard(s[q])) {
        ++count;
        if (!met(e, q, c, t)) return -1;
        break;
      }
      if (IsInside(s[q])) break;
    }
  }
  return count;
}

}  // namespace

bool PlugInsideWallCore(const VoxelGrid& grid, int64_t mid, const Coord& dir, int ring_radius,
                        int depth) {
  const auto st = grid.strides();
  const VoxelState* s = grid.states().data();
  const int met = ForEachDataMetAcross(
      grid, mid, dir, ring_radius, [&](const Coord& e, int64_t q, Coord c, int) {
        // Past the hard run: the outside within `depth` non-hard voxels, or the solid.
        const int64_t step = e.x * st[0] + e.y * st[1] + e.z * st[2];
        for (int past = 0; past < depth;) {
          q += step;
          c = {c.x + e.x, c.y + e.y, c.z + e.z};
          if (!grid.Contains(c)) return false;
          if (IsOutside(s[q])) return true;
          if (!IsHard(s[q])) ++past;
        }
        return false;
      });
  return met > 0;
}

bool PlugBetweenWallFaces(const VoxelGrid& grid, const HardVoxelPoints& points, int64_t mid,
                          const Coord& dir, int ring_radius, int narrow_steps,
                          double min_spread) {
  int two_surfaces = 0, farthest = 0;
  const int met = ForEachDataMetAcross(
      grid, mid, dir, ring_radius, [&](const Coord&, int64_t, const Coord& c, int t) {
        farthest = std::max(farthest, t);
        if (points.PlaneSpread(grid, {c.x - 1, c.y - 1, c.z - 1}, {c.x + 1, c.y + 1, c.z + 1}) >=
            min_spread) {
          ++two_surfaces;
        }
        return true;
      });
  return farthest > narrow_steps && 2 * two_surfaces > met;
}

}  // namespace membrane

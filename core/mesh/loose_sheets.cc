#include "core/mesh/loose_sheets.h"

#include <array>
#include <cstdint>
#include <vector>

#include "core/engine/voxel_state_words.h"

namespace membrane {
int64_t RemoveLooseSheets(VoxelGrid& grid) {
  // A component holds an inside voxel iff one of its boundary voxels touches one: any 26-path
  // from a boundary voxel to the rest of its component leaves the boundary voxels through an
  // inside voxel. So flood the boundary voxels from those that touch an inside voxel.
  const std::array<int64_t, 26>& off = grid.neighbour_offsets();
  const VoxelState* s = grid.states().data();
  std::vector<char> kept(static_cast<size_t>(grid.size()), 0);
  std::vector<int64_t> stack;
  std::vector<int64_t> boundary;
  const auto& d = grid.dims();
  for (int z = 1; z < d[2] - 1; ++z)
    for (int y = 1; y < d[1] - 1; ++y)
      for (int x = 1; x < d[0] - 1; ++x) {
        const int64_t i = grid.Index(x, y, z);
        // Eight voxels at a time where none is a boundary voxel (nearly everywhere).
        if ((x - 1) % 8 == 0 && x + 8 <= d[0] - 1 && !AnyBoundary8(s + i)) {
          x += 7;
          continue;
        }
        if (!IsBoundary(s[i])) continue;
        boundary.push_back(i);
        for (int64_t o : off)
          if (IsInside(s[i + o])) {
            kept[i] = 1;
            stack.push_back(i);
            break;
          }
      }
  while (!stack.empty()) {
    const int64_t i = stack.back();
    stack.pop_back();
    for (int64_t o : off) {
      const int64_t j = i + o;
      if (kept[j] || !IsBoundary(s[j]) || grid.OnArrayBorder(grid.CoordOf(j))) continue;
      kept[j] = 1;
      stack.push_back(j);
    }
  }
  int64_t removed = 0;
  for (int64_t i : boundary)
    if (!kept[i]) {
      grid.set(i, OutsideState(0));
      ++removed;
    }
  return removed;
}

}  // namespace membrane

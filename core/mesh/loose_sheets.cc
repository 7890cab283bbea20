#include "core/mesh/loose_sheets.h"

#include <array>
#include <cstdint>
#include <vector>

#include "core/base/parallel_tasks.h"
#include "core/engine/flat_bitset.h"
#include "core/engine/voxel_state_words.h"

namespace membrane {
int64_t RemoveLooseSheets(VoxelGrid& grid, int threads) {
  // A component holds an inside voxel iff one of its boundary voxels touches one: any 26-path
  // from a boundary voxel to the rest of its component leaves the boundary voxels through an
  // inside voxel. So flood the boundary voxels from those that touch an inside voxel. The scan
  // goes plane by plane on the threads (each plane marks and lists its own voxels); the kept
  // set is the flood's closure, the same in any order.
  const std::array<int64_t, 26>& off = grid.neighbour_offsets();
  const VoxelState* s = grid.states().data();
  const auto& d = grid.dims();
  // One bit a voxel: the flood's marks are few (the membrane's voxels), and a byte a voxel
  // cleared up front was a pass of its own over a grid of 2e9 voxels.
  FlatBitset kept(grid.size());
  const int inner_planes = d[2] > 2 ? d[2] - 2 : 0;
  std::vector<std::vector<int64_t>> plane_boundary(inner_planes), plane_seeds(inner_planes);
  RunTasks(threads, inner_planes, [&](int, int64_t task) {
    const int z = static_cast<int>(task) + 1;
    std::vector<int64_t>& boundary = plane_boundary[task];
    std::vector<int64_t>& seeds = plane_seeds[task];
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
            seeds.push_back(i);  // marked kept below: planes may share a word of bits
            break;
          }
      }
  });
  std::vector<int64_t> stack;
  for (std::vector<int64_t>& seeds : plane_seeds) {
    for (int64_t i : seeds) kept.set(i);
    stack.insert(stack.end(), seeds.begin(), seeds.end());
    std::vector<int64_t>().swap(seeds);
  }
  while (!stack.empty()) {
    const int64_t i = stack.back();
    stack.pop_back();
    for (int64_t o : off) {
      const int64_t j = i + o;
      if (kept.test(j) || !IsBoundary(s[j]) || grid.OnArrayBorder(grid.CoordOf(j))) continue;
      kept.set(j);
      stack.push_back(j);
    }
  }
  int64_t removed = 0;
  for (const std::vector<int64_t>& boundary : plane_boundary)
    for (int64_t i : boundary)
      if (!kept.test(i)) {
        grid.set(i, OutsideState(0));
        ++removed;
      }
  return removed;
}

}  // namespace membrane

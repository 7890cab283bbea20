#include "core/mesh/cave_filling.h"

#include <bit>
#include <cstdint>
#include <vector>

#include "core/base/parallel_tasks.h"
#include "core/engine/flat_bitset.h"
#include "core/engine/local_topology.h"
#include "core/engine/voxel_state_words.h"
#include "core/mesh/border_flood.h"
#include "core/mesh/voxel_bit_masks.h"

namespace membrane {
namespace {

// The outside voxels among the eight from `states` on whose bits in `near` are clear, as the low
// byte (bit k for voxel k).
uint64_t Caves8(const VoxelState* states, const FlatBitset& near, int64_t first) {
  const uint64_t outside = (LoadStates8(states) >> 7) & kLowBits8;  // 1 per outside voxel
  return ((outside * 0x0102040810204080ull) >> 56) & ~EightBits(near, first);
}

}  // namespace

int64_t FillCaves(VoxelGrid& grid, int threads) {
  const VoxelState* s = grid.states().data();
  const auto& d = grid.dims();
  // Bits, 64 voxels a word: two grid-sized masks at a time, a quarter byte a voxel (on a
  // 10M-point cloud's grid of 2.2e9 voxels, 0.54 GB where byte masks took 4.3 GB). The flood
  // from the array border reads the rows next to every run of the exterior, most of the grid.
  // The filters' scratch is left unset (their first pass writes every word on the threads,
  // which then take the fresh pages' faults): a zeroed one would be a serial memset of the
  // grid's bits on the calling thread.
  FlatBitset near_exterior;
  {
    FlatBitset deep = OutsideBits(grid, threads);
    {
      FlatBitset scratch(grid.size(), nullptr, FlatBitset::Unset{});
      BoxFilterBits(d, /*erode=*/true, deep, scratch, threads);
    }
    near_exterior = FloodFromBorder(d, deep, threads);
  }
  {
    FlatBitset scratch(grid.size(), nullptr, FlatBitset::Unset{});
    BoxFilterBits(d, /*erode=*/false, near_exterior, scratch, threads);
  }

  // Each inner plane lists its caves in index order; the lists joined in plane order are the
  // caves in index order whatever the thread count.
  std::vector<std::vector<int64_t>> plane_caves(d[2]);
  RunTasks(threads, d[2] > 2 ? d[2] - 2 : 0, [&](int, int64_t task) {
    const int z = static_cast<int>(task) + 1;
    std::vector<int64_t>& found = plane_caves[z];
    for (int y = 1; y < d[1] - 1; ++y) {
      const int64_t row = grid.Index(0, y, z);
      int x = 1;
      // Eight voxels at a time (none is a cave nearly everywhere).
      for (; x + 8 <= d[0] - 1; x += 8) {
        for (uint64_t caves = Caves8(s + row + x, near_exterior, row + x); caves != 0;
             caves &= caves - 1) {
          found.push_back(row + x + std::countr_zero(caves));
        }
      }
      for (; x < d[0] - 1; ++x) {
        if (IsOutside(s[row + x]) && !near_exterior.test(row + x)) found.push_back(row + x);
      }
    }
  });
  near_exterior = FlatBitset();
  std::vector<int64_t> caves;
  for (std::vector<int64_t>& found : plane_caves) caves.insert(caves.end(), found.begin(), found.end());
  plane_caves.clear();

  auto solid = [](VoxelState v) { return !IsOutside(v); };
  int64_t filled = 0;
  for (bool progress = true; progress && !caves.empty();) {
    progress = false;
    size_t kept = 0;
    for (int64_t i : caves) {
      if (IsSimple(NeighbourhoodMask(grid, i, solid))) {
        grid.set(i, kBoundarySoft);
        ++filled;
        progress = true;
      } else {
        caves[kept++] = i;
      }
    }
    caves.resize(kept);
  }
  return filled;
}

}  // namespace membrane

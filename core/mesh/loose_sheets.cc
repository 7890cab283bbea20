#include "core/mesh/loose_sheets.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <vector>

#include "core/base/parallel_tasks.h"
#include "core/engine/flat_bitset.h"
#include "core/engine/voxel_state_words.h"

namespace membrane {
namespace {

// Planes of a slab, at least.
constexpr int kMinSlabPlanes = 8;

// The kept bits on slabs: two slabs' planes may share a word where they meet, and a slab
// reads its neighbours' face plane between rounds, so shared words are read and set atomically.
bool Test(FlatBitset& bits, int64_t i) {
  return (std::atomic_ref<uint64_t>(bits.words()[i >> 6]).load(std::memory_order_relaxed) >>
          (i & 63)) & 1;
}

// The flood from the seeds through boundary voxels, on `slabs` slabs of the inner planes
// (plane_boundary[k] and plane_seeds[k] are plane k + 1's), in rounds: each slab floods its own
// planes; between rounds each slab seeds the unkept boundary voxels of its two face planes with
// a kept 26-neighbour across the face; the rounds end when no slab has a seed. The kept set is
// the flood's closure, the same as the one-thread flood's.
void FloodOnSlabs(const VoxelGrid& grid, const std::vector<std::vector<int64_t>>& plane_boundary,
                  std::vector<std::vector<int64_t>>& plane_seeds, int threads, int slabs,
                  FlatBitset& kept) {
  const std::array<int64_t, 26>& off = grid.neighbour_offsets();
  const VoxelState* s = grid.states().data();
  const int inner_planes = static_cast<int>(plane_boundary.size());
  const int64_t plane = int64_t{grid.dims()[0]} * grid.dims()[1];
  slabs = std::clamp(slabs, 1, std::max(inner_planes, 1));
  // Slab k holds the inner planes [first[k], first[k + 1]) (array planes one more).
  std::vector<int> first(slabs + 1);
  for (int k = 0; k <= slabs; ++k) first[k] = static_cast<int>(int64_t{inner_planes} * k / slabs);
  std::vector<std::vector<int64_t>> stacks(slabs);
  // Marks the voxels of `stack` (slab k's seeds; those already kept are dropped) and floods
  // from them inside the slab. Words wholly inside the slab's planes are its own: plain reads
  // and writes, where an atomic OR is a locked instruction.
  auto flood = [&](int k, std::vector<int64_t>& stack) {
    const int z0 = first[k] + 1, z1 = first[k + 1] + 1;  // array planes [z0, z1)
    const int64_t begin = z0 * plane, end = z1 * plane;  // the slab's voxels
    const int64_t own_lo = (begin + 63) >> 6, own_hi = end >> 6;  // [own_lo, own_hi)
    uint64_t* const words = kept.words();
    // True when j was not kept and is now.
    auto mark = [&](int64_t j) {
      const int64_t w = j >> 6;
      const uint64_t bit = uint64_t{1} << (j & 63);
      if (w >= own_lo && w < own_hi) {
        if (words[w] & bit) return false;
        words[w] |= bit;
        return true;
      }
      return (std::atomic_ref<uint64_t>(words[w]).fetch_or(bit, std::memory_order_relaxed) & bit) == 0;
    };
    size_t seeds = 0;
    for (int64_t i : stack)
      if (mark(i)) stack[seeds++] = i;
    stack.resize(seeds);
    while (!stack.empty()) {
      const int64_t i = stack.back();
      stack.pop_back();
      for (int64_t o : off) {
        const int64_t j = i + o;
        if (j < begin || j >= end) continue;  // another slab's (a compare, not a division)
        if (Test(kept, j) || !IsBoundary(s[j]) || grid.OnArrayBorder(grid.CoordOf(j))) continue;
        mark(j);
        stack.push_back(j);
      }
    }
  };
  RunTasks(threads, slabs, [&](int, int64_t k) {
    for (int p = first[k]; p < first[k + 1]; ++p) {
      stacks[k].insert(stacks[k].end(), plane_seeds[p].begin(), plane_seeds[p].end());
      std::vector<int64_t>().swap(plane_seeds[p]);
    }
    flood(static_cast<int>(k), stacks[k]);
  });
  // The unkept boundary voxels of inner plane p with a kept voxel in array plane p + 1 + dir.
  auto face_seeds = [&](int p, int dir, std::vector<int64_t>& seeds) {
    for (int64_t i : plane_boundary[p]) {
      if (Test(kept, i)) continue;
      for (int64_t o : off) {
        const int64_t j = i + o;
        const bool across = dir < 0 ? j < (p + 1) * plane : j >= (p + 2) * plane;
        if (across && Test(kept, j)) {
          seeds.push_back(i);
          break;
        }
      }
    }
  };
  for (;;) {
    std::atomic<bool> seeded{false};
    RunTasks(threads, slabs, [&](int, int64_t k) {
      if (k > 0) face_seeds(first[k], -1, stacks[k]);
      if (k + 1 < slabs) face_seeds(first[k + 1] - 1, 1, stacks[k]);
      if (!stacks[k].empty()) seeded.store(true, std::memory_order_relaxed);
    });
    if (!seeded.load()) break;
    RunTasks(threads, slabs, [&](int, int64_t k) { flood(static_cast<int>(k), stacks[k]); });
  }
}

int64_t RemoveLooseSheetsOn(VoxelGrid& grid, int threads, int slabs) {
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
  FlatBitset kept(grid.size(), nullptr, FlatBitset::Unset{});
  kept.set_threads(threads);
  kept.clear_all();  // on the threads: the first writes of a large bitset are page faults
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
  if (slabs <= 0) {
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
  } else {
    FloodOnSlabs(grid, plane_boundary, plane_seeds, threads, slabs, kept);
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

}  // namespace

int64_t RemoveLooseSheets(VoxelGrid& grid, int threads) {
  const auto& d = grid.dims();
  const bool slabbed = threads > 1 && grid.size() >= kMinSplitGridVoxels && d[2] >= 2 * kMinSlabPlanes;
  // Many slabs a thread, as the cave filling's flood: a round waits for its last slab.
  return RemoveLooseSheetsOn(grid, threads, slabbed ? std::min(d[2] / kMinSlabPlanes, 16 * threads) : 0);
}

int64_t RemoveLooseSheetsOnSlabs(VoxelGrid& grid, int threads, int slabs) {
  return RemoveLooseSheetsOn(grid, threads, std::max(slabs, 1));
}

}  // namespace membrane

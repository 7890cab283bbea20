#include "core/mesh/cave_filling.h"

#include <cstdint>
#include <cstring>
#include <vector>

#include "core/base/parallel_tasks.h"
#include "core/engine/huge_page_allocator.h"
#include "core/engine/local_topology.h"
#include "core/engine/voxel_state_words.h"

namespace membrane {
namespace {

// One byte per voxel, touched once: 2 MB pages where the kernel gives them (the 4 KB page faults
// of these four grid-sized arrays would take as long as the filling itself).
using Mask = std::vector<char, HugePageAllocator<char>>;

// mask := for each voxel, the AND (erode) or OR (dilate) of the mask over its 3x3x3 box, as
// three 1-D passes; voxels beyond the array read as `beyond`. Inner loops run along x over
// whole rows with no test inside (the row ends apart), so they vectorize. Each pass writes one
// z plane per task from planes of the previous one, so the planes share `threads` and the
// result does not depend on the count. `tmp` is scratch of the mask's size.
template <bool kErode>
void BoxFilter(const VoxelGrid& grid, Mask& mask, Mask& tmp, char beyond, int threads) {
  const int nx = grid.dim(0), ny = grid.dim(1), nz = grid.dim(2);
  const int64_t sy = nx, sz = int64_t{nx} * ny;
  auto combine = [](char a, char b, char c) -> char { return kErode ? (a & b & c) : (a | b | c); };
  // The tasks copy what they read into locals: a byte store could alias anything reached
  // through the closure, which would keep the row loops from vectorizing.
  // Along x.
  RunTasks(threads, nz, [&](int, int64_t z) {
    const int w = nx;
    const char out = beyond;
    const char* const from = mask.data();
    char* const to = tmp.data();
    for (int64_t row = z * ny; row < (z + 1) * ny; ++row) {
      const char* m = from + row * w;
      char* t = to + row * w;
      if (w == 1) {
        t[0] = combine(out, m[0], out);
        continue;
      }
      t[0] = combine(out, m[0], m[1]);
      for (int x = 1; x + 1 < w; ++x) t[x] = combine(m[x - 1], m[x], m[x + 1]);
      t[w - 1] = combine(m[w - 2], m[w - 1], out);
    }
  });
  mask.swap(tmp);
  // Along y, then z: whole rows at a time.
  const std::vector<char> beyond_row(nx, beyond);
  for (int axis = 1; axis < 3; ++axis) {
    const int n = axis == 1 ? ny : nz;
    const int64_t step = axis == 1 ? sy : sz;
    RunTasks(threads, nz, [&](int, int64_t z) {
      const int w = nx, rows = ny, count = n;
      const int64_t row_step = sy, plane_step = sz, axis_step = step;
      const bool along_y = axis == 1;
      const char* const from = mask.data();
      const char* const outside_row = beyond_row.data();
      char* const to = tmp.data();
      for (int y = 0; y < rows; ++y) {
        const int64_t i = y * row_step + z * plane_step;
        const int c = along_y ? y : static_cast<int>(z);
        const char* lo = c > 0 ? from + i - axis_step : outside_row;
        const char* mid = from + i;
        const char* hi = c + 1 < count ? from + i + axis_step : outside_row;
        char* t = to + i;
        for (int x = 0; x < w; ++x) t[x] = combine(lo[x], mid[x], hi[x]);
      }
    });
    mask.swap(tmp);
  }
}

// For the voxels from..to (one row segment): each run of open voxels (deep, not reached) gets
// its first voxel marked reached and pushed on `stack`. Eight voxels at a time where they are
// all closed, or all open inside a run already seeded: the flood scans every filled run's four
// neighbour rows, and most of those bytes are one or the other.
void SeedRuns(const char* deep, char* reached, int64_t from, int64_t to,
              std::vector<int64_t>& stack) {
  constexpr uint64_t kAllOpen = 0x0101010101010101ull;
  bool in_run = false;
  for (int64_t i = from; i <= to;) {
    if (to - i >= 7) {
      uint64_t d, r;
      std::memcpy(&d, deep + i, 8);
      std::memcpy(&r, reached + i, 8);
      const uint64_t open = d & ~r;  // bytes are 0 or 1
      if (open == 0) {
        in_run = false;
        i += 8;
        continue;
      }
      if (open == kAllOpen && in_run) {
        i += 8;
        continue;
      }
    }
    const bool open = deep[i] && !reached[i];
    if (open && !in_run) {
      reached[i] = 1;
      stack.push_back(i);
    }
    in_run = open;
    ++i;
  }
}

// reached := the voxels of `deep` 6-connected to a deep voxel on the array border.
Mask FloodFromBorder(const VoxelGrid& grid, const Mask& deep) {
  const int n[3] = {grid.dim(0), grid.dim(1), grid.dim(2)};
  const int64_t step[3] = {1, n[0], int64_t{n[0]} * n[1]};
  Mask reached(deep.size(), 0);
  std::vector<int64_t> stack;
  // The border voxels are marked but never expanded (their neighbours may not exist). Every
  // voxel one layer in is interior; those touching a deep border voxel seed the flood, and
  // every voxel the flood reaches from them is interior or already marked.
  for (int z = 0; z < n[2]; ++z)
    for (int y = 0; y < n[1]; ++y)
      for (int x = 0; x < n[0]; ++x) {
        const int c[3] = {x, y, z};
        int on_border = 0, on_layer1 = 0;
        for (int a = 0; a < 3; ++a) {
          on_border |= c[a] == 0 || c[a] == n[a] - 1;
          on_layer1 |= c[a] == 1 || c[a] == n[a] - 2;
        }
        if (!on_border && !on_layer1) {
          x = n[0] - 3;  // jump to the far layer-1 voxel of this row
          continue;
        }
        const int64_t i = grid.Index(x, y, z);
        if (on_border) {
          if (deep[i]) reached[i] = 1;
          continue;
        }
        if (!deep[i]) continue;
        for (int a = 0; a < 3; ++a)
          if ((c[a] == 1 && deep[i - step[a]]) || (c[a] == n[a] - 2 && deep[i + step[a]])) {
            reached[i] = 1;
            stack.push_back(i);
            break;
          }
      }
  // Scanline flood: each popped seed is extended into its whole run along x, and each run
  // seeds the rows next to it; memory is read row by row instead of voxel by voxel.
  while (!stack.empty()) {
    const int64_t seed = stack.back();
    stack.pop_back();
    int64_t lo = seed, hi = seed;
    while (deep[lo - 1] && !reached[lo - 1]) reached[--lo] = 1;
    while (deep[hi + 1] && !reached[hi + 1]) reached[++hi] = 1;
    for (int a = 1; a < 3; ++a)
      for (int64_t offset : {-step[a], step[a]})
        SeedRuns(deep.data(), reached.data(), lo + offset, hi + offset, stack);
  }
  return reached;
}

// True when one of the 8 voxels at `states` is outside while its `near` byte is 0.
bool AnyCave(const VoxelState* states, const char* near) {
  uint64_t n;
  std::memcpy(&n, near, 8);
  const uint64_t outside = (LoadStates8(states) >> 7) & kLowBits8;  // 1 per outside voxel
  return (outside & ~n) != 0;                                        // near bytes are 0 or 1
}

}  // namespace

int64_t FillCaves(VoxelGrid& grid, int threads) {
  const int64_t n = grid.size();
  const VoxelState* s = grid.states().data();
  const auto& d = grid.dims();
  const int64_t plane = int64_t{d[0]} * d[1];
  // The grid-wide passes go plane by plane on the threads (the first touch of each mask's
  // pages too, which the kernel clears on the touching thread).
  Mask deep(n);
  // A raw pointer copied into the task: a byte store through a reference's target could
  // alias the vector itself, which would keep the loop from vectorizing.
  char* const deep_bytes = deep.data();
  RunTasks(threads, d[2], [deep_bytes, s, plane](int, int64_t z) {
    for (int64_t i = z * plane; i < (z + 1) * plane; ++i) deep_bytes[i] = IsOutside(s[i]) ? 1 : 0;
  });
  // Two grid-sized masks at a time, not three: the erosion's scratch goes before the flood
  // makes its mask, and `deep`, read by the flood alone, is the dilation's scratch (the filter
  // writes every byte of its scratch before reading it). On a 10M-point cloud's grid of 2e9
  // voxels a mask is 2 GB.
  {
    Mask scratch(n);
    BoxFilter</*kErode=*/true>(grid, deep, scratch, /*beyond=*/1, threads);
  }
  Mask near_exterior = FloodFromBorder(grid, deep);
  BoxFilter</*kErode=*/false>(grid, near_exterior, deep, /*beyond=*/0, threads);
  Mask().swap(deep);

  // Each inner plane lists its caves in index order; the lists joined in plane order are the
  // caves in index order whatever the thread count.
  std::vector<std::vector<int64_t>> plane_caves(d[2]);
  RunTasks(threads, d[2] > 2 ? d[2] - 2 : 0, [&](int, int64_t task) {
    const int z = static_cast<int>(task) + 1;
    std::vector<int64_t>& found = plane_caves[z];
    for (int y = 1; y < d[1] - 1; ++y) {
      const int64_t row = grid.Index(0, y, z);
      for (int x = 1; x < d[0] - 1;) {
        // Eight voxels at a time where none is a cave (nearly everywhere).
        if (x + 8 <= d[0] - 1 && !AnyCave(s + row + x, near_exterior.data() + row + x)) {
          x += 8;
          continue;
        }
        if (IsOutside(s[row + x]) && !near_exterior[row + x]) found.push_back(row + x);
        ++x;
      }
    }
  });
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

#include "core/mesh/cave_filling.h"

#include <cstdint>
#include <cstring>
#include <vector>

#include "core/base/parallel_tasks.h"
#include "core/engine/huge_page_allocator.h"
#include "core/engine/local_topology.h"
#include "core/engine/voxel_state_words.h"
#include "core/mesh/border_flood.h"

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
  // Two grid-sized masks at a time, not three: the erosion's scratch goes before the
  // dilation makes its mask, and the flood holds two bit masks (a quarter byte a voxel) beside
  // `deep`. On a 10M-point cloud's grid of 2e9 voxels a mask is 2 GB.
  {
    Mask scratch(n);
    BoxFilter</*kErode=*/true>(grid, deep, scratch, /*beyond=*/1, threads);
  }
  // The flood runs on bits (64 voxels a word): it reads the rows next to every run of the
  // exterior, most of the grid. Its result goes back into `deep`'s bytes for the dilation.
  {
    const FlatBitset reached = FloodFromBorder(d, PackVoxelBits(deep.data(), n, threads));
    UnpackVoxelBits(reached, deep.data(), threads);
  }
  Mask near_exterior(n);
  BoxFilter</*kErode=*/false>(grid, deep, near_exterior, /*beyond=*/0, threads);
  near_exterior.swap(deep);
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

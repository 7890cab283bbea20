#include "core/engine/outside_runs.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <vector>

#include "core/base/parallel_tasks.h"

namespace membrane {
namespace {

constexpr uint64_t kHigh = 0x8080808080808080ull;  // the outside bit of eight states
static_assert(kOutsideBit == 0x80, "the word scans below read the outside bit of voxel_state.h");

// The non-outside bits (0x80 of each byte) of the eight states from row[x]; states past
// `count` read as outside.
uint64_t SolidOfEight(const VoxelState* row, int x, int count) {
  uint64_t w;
  if (x + 8 <= count) {
    std::memcpy(&w, row + x, sizeof w);
  } else {
    w = ~uint64_t{0};
    if (x < count) std::memcpy(&w, row + x, static_cast<size_t>(count - x));
  }
  return ~w & kHigh;
}

// Visits every run boundary of the rows that pass through planes [z0, z1), each row's in
// rising order: on(d, row, coordinate, end), with end false at a run's first voxel and true at
// its last. A run's last voxel is seen one step past it (at the outside voxel after it or the
// array's end), so planes [z0, z1) report the z runs' first voxels in [z0, z1) and their last
// in [z0 - 1, z1 - 1), and the slab that ends the array the last ones at nz - 1 too.
template <typename On>
void ScanSlab(const VoxelGrid& grid, int z0, int z1, On&& on) {
  const int nx = grid.dim(0), ny = grid.dim(1), nz = grid.dim(2);
  const VoxelState* s = grid.states().data();
  // Rows past the array's rows and planes read as outside: then every boundary is a change
  // between a row and the one before it (y) or under it (z), whatever the row.
  const std::vector<VoxelState> open(static_cast<size_t>(nx), OutsideState(1));
  const int z_end = z1 == nz ? nz + 1 : z1;
  for (int z = z0; z < z_end; ++z)
    for (int y = 0; y <= ny; ++y) {
      // Row y of plane z; the row before it in the plane; the row under it in plane z - 1.
      const VoxelState* here = z < nz && y < ny ? s + grid.Index(0, y, z) : open.data();
      const VoxelState* before = z < nz && y > 0 ? s + grid.Index(0, y - 1, z) : open.data();
      const VoxelState* under = z > 0 && y < ny ? s + grid.Index(0, y, z - 1) : open.data();
      const size_t x_row = static_cast<size_t>(y) + static_cast<size_t>(ny) * z;
      const size_t y_row = static_cast<size_t>(nx) * z, z_row = static_cast<size_t>(nx) * y;
      uint64_t carry = 0;  // the last state of the word before: 0x80 when not outside
      // The boundaries met in the eight states from x, their non-outside bits n (here), b
      // (before) and u (under).
      auto word = [&](int x, uint64_t n, uint64_t b, uint64_t u) {
        const uint64_t previous = (n << 8) | carry;
        carry = n >> 56;
        for (uint64_t m = (n & ~previous) | (~n & kHigh & previous); m != 0; m &= m - 1) {
          const int k = __builtin_ctzll(m) / 8;
          const bool end = ((n >> (8 * k)) & 0x80) == 0;
          on(0, x_row, end ? x + k - 1 : x + k, end);
        }
        for (uint64_t m = n ^ b; m != 0; m &= m - 1) {
          const int k = __builtin_ctzll(m) / 8;
          const bool end = (b >> (8 * k)) & 0x80;
          on(1, static_cast<size_t>(x + k) + y_row, end ? y - 1 : y, end);
        }
        for (uint64_t m = n ^ u; m != 0; m &= m - 1) {
          const int k = __builtin_ctzll(m) / 8;
          const bool end = (u >> (8 * k)) & 0x80;
          on(2, static_cast<size_t>(x + k) + z_row, end ? z - 1 : z, end);
        }
      };
      // 64 states at a time, passed over where the three rows are all outside, or all not
      // outside after a state not outside: no boundary there (most of a shrunk grid).
      int x = 0;
      for (; x + 64 <= nx; x += 64) {
        uint64_t h[8], b[8], u[8];
        std::memcpy(h, here + x, sizeof h);
        std::memcpy(b, before + x, sizeof b);
        std::memcpy(u, under + x, sizeof u);
        uint64_t all = kHigh, any = 0;
        for (int k = 0; k < 8; ++k) {
          all &= h[k] & b[k] & u[k];
          any |= h[k] | b[k] | u[k];
        }
        if (((all & kHigh) == kHigh && carry == 0) || ((any & kHigh) == 0 && carry != 0))
          continue;
        for (int k = 0; k < 8; ++k)
          word(x + 8 * k, ~h[k] & kHigh, ~b[k] & kHigh, ~u[k] & kHigh);
      }
      // The rest, and one state past the row: a run at its end ends there.
      for (; x <= nx; x += 8)
        word(x, SolidOfEight(here, x, nx), SolidOfEight(before, x, nx),
             SolidOfEight(under, x, nx));
    }
}

}  // namespace

std::optional<OutsideRuns> OutsideRuns::Read(const VoxelGrid& grid, int threads,
                                             int64_t max_bytes) {
  OutsideRuns r;
  r.dims_ = grid.dims();
  const int nx = r.dims_[0], ny = r.dims_[1], nz = r.dims_[2];
  const size_t rows[3] = {static_cast<size_t>(ny) * nz, static_cast<size_t>(nx) * nz,
                          static_cast<size_t>(nx) * ny};
  const int slabs = std::clamp(threads, 1, std::max(nz, 1));
  auto slab_begin = [&](int64_t slab) { return static_cast<int>(nz * slab / slabs); };
  // Counts: the runs ending per x and y row in first_[d][row + 1]; per z column and slab, the
  // runs ending in the slab (their sum over the slabs before a slab is where its runs go).
  for (int d = 0; d < 2; ++d) r.first_[d].assign(rows[d] + 1, 0);
  std::vector<std::vector<uint32_t>> z_ends(static_cast<size_t>(slabs));
  RunTasks(slabs, slabs, [&](int, int64_t slab) {
    std::vector<uint32_t>& ends = z_ends[static_cast<size_t>(slab)];
    ends.assign(rows[2], 0);
    ScanSlab(grid, slab_begin(slab), slab_begin(slab + 1),
             [&](int d, size_t row, int, bool end) {
               if (!end) return;
               if (d == 2) {
                 ++ends[row];
               } else {
                 ++r.first_[d][row + 1];
               }
             });
  });
  r.first_[2].assign(rows[2] + 1, 0);
  for (size_t c = 0; c < rows[2]; ++c) {
    uint32_t before = 0;  // the column's runs ended in the slabs before, at most nz / 2
    for (std::vector<uint32_t>& ends : z_ends) {
      const uint32_t count = ends[c];
      ends[c] = before;
      before += count;
    }
    r.first_[2][c + 1] = before;
  }
  int64_t runs = 0;
  for (int d = 0; d < 3; ++d) {
    uint64_t total = 0;
    for (size_t row = 0; row < rows[d]; ++row) {
      total += r.first_[d][row + 1];
      if (total > std::numeric_limits<uint32_t>::max()) return std::nullopt;
      r.first_[d][row + 1] = static_cast<uint32_t>(total);
    }
    runs += static_cast<int64_t>(total);
  }
  if (runs > max_bytes / 8) return std::nullopt;
  // The z columns' slab offsets were counted from 0 a column: add each column's start.
  for (std::vector<uint32_t>& ends : z_ends)
    for (size_t c = 0; c < rows[2]; ++c) ends[c] += r.first_[2][c];
  for (int d = 0; d < 3; ++d) {
    const size_t n = r.first_[d][rows[d]];
    r.lo_[d].resize(n);
    r.hi_[d].resize(n);
  }
  // Writing: a run's first voxel at its index, its last too, then the index moves on. The x
  // and y rows' indices start at first_ (a row lies in one plane, of one slab); the z
  // columns' at the runs ended in the slabs before.
  RunTasks(slabs, slabs, [&](int, int64_t slab) {
    std::vector<uint32_t>& z_next = z_ends[static_cast<size_t>(slab)];
    std::vector<uint32_t> y_next(static_cast<size_t>(nx));
    int plane = -1;
    size_t x_row = std::numeric_limits<size_t>::max();
    uint32_t x_next = 0;
    ScanSlab(grid, slab_begin(slab), slab_begin(slab + 1),
             [&](int d, size_t row, int t, bool end) {
               uint32_t* next;
               if (d == 0) {
                 if (row != x_row) {
                   x_row = row;
                   x_next = r.first_[0][row];
                 }
                 next = &x_next;
               } else if (d == 1) {
                 const int z = static_cast<int>(row / static_cast<size_t>(nx));
                 if (z != plane) {
                   plane = z;
                   for (int x = 0; x < nx; ++x)
                     y_next[static_cast<size_t>(x)] =
                         r.first_[1][static_cast<size_t>(x) + static_cast<size_t>(nx) * z];
                 }
                 next = &y_next[row - static_cast<size_t>(nx) * z];
               } else {
                 next = &z_next[row];
               }
               if (end) {
                 r.hi_[d][(*next)++] = t;
               } else {
                 r.lo_[d][*next] = t;
               }
             });
  });
  return r;
}

int OutsideRuns::WalkOutside(const Coord& c, int d, int sign) const {
  const int last = dims_[d] - 1;
  const int t = c[d] + sign;
  if (t <= 0 || t >= last) return t;
  const size_t row = AxisRowOf(dims_, d, c);
  const int32_t* lo = lo_[d].data();
  const int32_t* hi = hi_[d].data();
  const uint32_t begin = first_[d][row], end = first_[d][row + 1];
  if (sign > 0) {
    // The first run that ends at t or past it: its first voxel at or past t stops the walk.
    const int32_t* run = std::lower_bound(hi + begin, hi + end, t);
    if (run == hi + end) return last;
    return std::min(std::max(lo[run - hi], t), last);
  }
  // The last run that starts at t or before it.
  const int32_t* run = std::upper_bound(lo + begin, lo + end, t);
  if (run == lo + begin) return 0;
  return std::max(std::min(hi[run - lo - 1], t), 0);
}

int64_t OutsideRuns::runs() const {
  return static_cast<int64_t>(lo_[0].size() + lo_[1].size() + lo_[2].size());
}

}  // namespace membrane

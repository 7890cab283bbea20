#include "core/engine/outside_blocks.h"

#include <algorithm>
#include <cstring>

#include "core/base/parallel_tasks.h"

namespace membrane {
namespace {

constexpr int kBlock = 8;
constexpr uint64_t kHigh = 0x8080808080808080ull;  // the outside bit of eight states
static_assert(kOutsideBit == 0x80, "the word test below reads the outside bit of voxel_state.h");

}  // namespace

OutsideBlocks::OutsideBlocks(const VoxelGrid& grid, int threads) {
  const auto& dims = grid.dims();
  for (int d = 0; d < 3; ++d) blocks_[d] = (dims[d] + kBlock - 1) / kBlock;
  // Each plane of blocks starts on a word of its own: the tasks write disjoint words.
  plane_bits_ = (static_cast<int64_t>(blocks_[0]) * blocks_[1] + 63) / 64 * 64;
  bits_.assign(static_cast<size_t>(plane_bits_ / 64 * blocks_[2]), 0);
  const VoxelState* states = grid.states().data();
  const int nx = dims[0];
  const int full = nx / kBlock;  // blocks with all eight columns in the array
  RunTasks(threads, blocks_[2], [&](int, int64_t bz) {
    // acc[bx]: the AND of the block's rows of eight states, so far.
    std::vector<uint64_t> acc(static_cast<size_t>(blocks_[0]));
    const int z0 = static_cast<int>(bz) * kBlock, z1 = std::min(z0 + kBlock, dims[2]);
    for (int by = 0; by < blocks_[1]; ++by) {
      std::fill(acc.begin(), acc.end(), kHigh);
      const int y0 = by * kBlock, y1 = std::min(y0 + kBlock, dims[1]);
      for (int z = z0; z < z1; ++z)
        for (int y = y0; y < y1; ++y) {
          const VoxelState* row = states + grid.Index(0, y, z);
          for (int bx = 0; bx < full; ++bx) {
            uint64_t w;
            std::memcpy(&w, row + bx * kBlock, sizeof w);
            acc[static_cast<size_t>(bx)] &= w;
          }
          for (int x = full * kBlock; x < nx; ++x)
            if (!IsOutside(row[x])) acc[static_cast<size_t>(full)] = 0;
        }
      for (int bx = 0; bx < blocks_[0]; ++bx) {
        if ((acc[static_cast<size_t>(bx)] & kHigh) != kHigh) continue;
        const int64_t bit = bz * plane_bits_ + bx + static_cast<int64_t>(blocks_[0]) * by;
        bits_[static_cast<size_t>(bit >> 6)] |= uint64_t{1} << (bit & 63);
      }
    }
  });
  for (int d = 0; d < 3; ++d) {
    const size_t rows = static_cast<size_t>(blocks_[(d + 1) % 3]) * blocks_[(d + 2) % 3];
    solid_lo_[d].assign(rows, blocks_[d]);
    solid_hi_[d].assign(rows, -1);
  }
  Coord b;
  for (b.z = 0; b.z < blocks_[2]; ++b.z)
    for (b.y = 0; b.y < blocks_[1]; ++b.y)
      for (b.x = 0; b.x < blocks_[0]; ++b.x) {
        if (AllOutside(b)) continue;
        for (int d = 0; d < 3; ++d) {
          const size_t row = AxisRowOf(blocks_, d, b);
          solid_lo_[d][row] = std::min(solid_lo_[d][row], b[d]);
          solid_hi_[d][row] = std::max(solid_hi_[d][row], b[d]);
        }
      }
}

int OutsideBlocks::WalkOutside(const VoxelGrid& grid, const Coord& c, int d, int sign) const {
  const int last = grid.dim(d) - 1;
  const int64_t step = sign * grid.strides()[d];
  Coord b{c.x / kBlock, c.y / kBlock, c.z / kBlock};
  const size_t row = AxisRowOf(blocks_, d, b);
  int t = c[d] + sign;
  int64_t u = grid.Index(c) + step;
  while (t > 0 && t < last) {
    b[d] = t / kBlock;
    // Every block from here to the border is outside: the ray is in the open.
    if (sign > 0 ? b[d] > solid_hi_[d][row] : b[d] < solid_lo_[d][row]) return sign > 0 ? last : 0;
    if (AllOutside(b)) {
      // Every voxel of the block on the ray is outside: on to the next block (or the border).
      const int next = sign > 0 ? std::min((t / kBlock + 1) * kBlock, last)
                                : std::max(t / kBlock * kBlock - 1, 0);
      u += (next - t) * grid.strides()[d];
      t = next;
      continue;
    }
    if (!IsOutside(grid.at(u))) break;
    t += sign;
    u += step;
  }
  return t;
}

}  // namespace membrane

#include "core/engine/packed_plane.h"

#include <algorithm>
#include <bit>
#include <vector>

#include "core/engine/rewritten_buffer.h"
#include "core/engine/word_blocks.h"

namespace membrane {

void PackedPlane::Assign(const FlatBitset& plane) {
  const int64_t words = static_cast<int64_t>(plane.word_count());
  const int64_t groups = (words + 63) / 64;
  // Every flag and rank is written below: no clearing.
  mixed_.resize(static_cast<size_t>(groups));
  ones_.resize(static_cast<size_t>(groups));
  rank_.resize(static_cast<size_t>(groups));
  const uint64_t* w = plane.words();
  // The plane's blocks of words (whole groups: a block is 512 of them) on its threads, in two
  // passes, so that the mixed words take their exact size (a vector grown by doubling would
  // hold up to twice it at the snapshot's peak): the flags and each block's own ranks, then,
  // once every block's count is known, the ranks made global and the mixed words copied. The
  // blocks are fixed by the plane's size, so the copy is the same for any thread count.
  static_assert(kWordBlock % 64 == 0);
  const int threads = plane.threads();
  std::vector<int64_t> block_mixed(static_cast<size_t>(WordBlockCount(threads, words)), 0);
  ForWordBlocks(threads, words, [&](int64_t block, int64_t begin, int64_t end) {
    int64_t mixed = 0;
    for (int64_t g = begin / 64; g * 64 < end; ++g) {
      rank_[static_cast<size_t>(g)] = mixed;
      uint64_t m = 0, o = 0;
      const int64_t last = std::min(end, (g + 1) * 64);
      for (int64_t k = g * 64; k < last; ++k) {
        const uint64_t x = w[k];
        o |= static_cast<uint64_t>(x == ~uint64_t{0}) << (k & 63);
        m |= static_cast<uint64_t>(x != 0 && x != ~uint64_t{0}) << (k & 63);
      }
      mixed_[static_cast<size_t>(g)] = m;
      ones_[static_cast<size_t>(g)] = o;
      mixed += std::popcount(m);
    }
    block_mixed[static_cast<size_t>(block)] = mixed;
  });
  int64_t total = 0;
  for (int64_t& count : block_mixed) {
    const int64_t before = total;
    total += count;
    count = before;  // the block's first rank
  }
  // A copy that needs more words than the buffer holds takes them with a sixteenth to spare:
  // grown by resize, the buffer doubled (a snapshot a few words larger than the last held up
  // to twice its words, 845 MB of copies instead of about 520 on the 10M-point bunny scan's
  // first fine plate).
  ResizeRewritten(words_, static_cast<size_t>(total), static_cast<size_t>(total / 16));
  uint64_t* out = words_.data();
  ForWordBlocks(threads, words, [&](int64_t block, int64_t begin, int64_t end) {
    const int64_t offset = block_mixed[static_cast<size_t>(block)];
    for (int64_t g = begin / 64; g * 64 < end; ++g) {
      int64_t& rank = rank_[static_cast<size_t>(g)];
      rank += offset;
      // Only the mixed words are read again, by their flags.
      int64_t next = rank;
      for (uint64_t m = mixed_[static_cast<size_t>(g)]; m != 0; m &= m - 1)
        out[next++] = w[g * 64 + std::countr_zero(m)];
    }
  });
}

int64_t PackedPlane::bytes() const {
  return static_cast<int64_t>(mixed_.capacity() * sizeof(uint64_t) +
                              ones_.capacity() * sizeof(uint64_t) +
                              rank_.capacity() * sizeof(int64_t) +
                              words_.capacity() * sizeof(uint64_t));
}

}  // namespace membrane

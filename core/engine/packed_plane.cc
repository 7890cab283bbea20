#include "core/engine/packed_plane.h"

#include <algorithm>

namespace membrane {

void PackedPlane::Assign(const FlatBitset& plane) {
  const int64_t words = static_cast<int64_t>(plane.word_count());
  const int64_t groups = (words + 63) / 64;
  mixed_.assign(static_cast<size_t>(groups), 0);
  ones_.assign(static_cast<size_t>(groups), 0);
  rank_.assign(static_cast<size_t>(groups), 0);
  const uint64_t* w = plane.words();
  // Two passes, so that the mixed words take their exact size: a vector grown by doubling
  // would hold up to twice it at the snapshot's peak.
  int64_t mixed = 0;
  for (int64_t g = 0; g < groups; ++g) {
    rank_[static_cast<size_t>(g)] = mixed;
    uint64_t m = 0, o = 0;
    const int64_t end = std::min(words, (g + 1) * 64);
    for (int64_t k = g * 64; k < end; ++k) {
      const uint64_t bit = uint64_t{1} << (k & 63);
      if (w[k] == ~uint64_t{0}) {
        o |= bit;
      } else if (w[k] != 0) {
        m |= bit;
      }
    }
    mixed_[static_cast<size_t>(g)] = m;
    ones_[static_cast<size_t>(g)] = o;
    mixed += std::popcount(m);
  }
  words_.resize(static_cast<size_t>(mixed));
  int64_t next = 0;
  for (int64_t k = 0; k < words; ++k) {
    if (w[k] != 0 && w[k] != ~uint64_t{0}) words_[static_cast<size_t>(next++)] = w[k];
  }
}

int64_t PackedPlane::bytes() const {
  return static_cast<int64_t>(mixed_.capacity() * sizeof(uint64_t) +
                              ones_.capacity() * sizeof(uint64_t) +
                              rank_.capacity() * sizeof(int64_t) +
                              words_.capacity() * sizeof(uint64_t));
}

}  // namespace membrane

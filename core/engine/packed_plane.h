// A read-only copy of a bit-plane that holds only its mixed words.
//
// The place finder keeps the anchors of every fitting plate (six planes, twelve with the
// anchor rows) from a snapshot until its chains are done, and reads them a bit at a time.
// Away from the membrane and the array border their words are all zeros (inside the solid) or
// all ones (the open outside), so the copy keeps two bits per word (mixed, all ones) and the
// mixed words alone: on a grid of 2e8 voxels about a sixth of a plane's bytes, where six
// planes held as they are would be most of the shrink's memory.
#ifndef MEMBRANE_CORE_ENGINE_PACKED_PLANE_H_
#define MEMBRANE_CORE_ENGINE_PACKED_PLANE_H_

#include <bit>
#include <cstdint>
#include <vector>

#include "core/engine/flat_bitset.h"

namespace membrane {

class PackedPlane {
 public:
  // Becomes a copy of `plane`, reusing its buffers (they never shrink: a snapshot's copies are
  // of similar sizes; a buffer that must grow holds the copy's words and a sixteenth more).
  // Runs on plane.threads() threads, with the same result for any count.
  void Assign(const FlatBitset& plane);

  // Bit i of the plane copied; i < its bits().
  bool test(int64_t i) const {
    const int64_t w = i >> 6;
    const size_t group = static_cast<size_t>(w >> 6);
    const uint64_t below = (uint64_t{1} << (w & 63)) - 1;
    const uint64_t bit = uint64_t{1} << (w & 63);
    const uint64_t mixed = mixed_[group];
    if ((mixed & bit) == 0) return (ones_[group] & bit) != 0;
    const uint64_t word = words_[static_cast<size_t>(rank_[group]) +
                                 static_cast<size_t>(std::popcount(mixed & below))];
    return (word >> (i & 63)) & 1;
  }

  // Bytes held (the flags, the ranks and the mixed words), for tests and statistics.
  int64_t bytes() const;

 private:
  // Per group of 64 words: bit k set when word 64 g + k is neither 0 nor all ones (mixed_),
  // or all ones (ones_); the mixed words of the groups before it (rank_); the mixed words in
  // order (words_).
  std::vector<uint64_t> mixed_;
  std::vector<uint64_t> ones_;
  std::vector<int64_t> rank_;
  std::vector<uint64_t> words_;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_PACKED_PLANE_H_

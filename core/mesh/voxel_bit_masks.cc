#include "core/mesh/voxel_bit_masks.h"

#include <algorithm>
#include <utility>

#include "core/base/parallel_tasks.h"
#include "core/engine/voxel_state_words.h"

namespace membrane {
namespace {

// Words per task: large enough that the tasks' overhead vanishes.
constexpr int64_t kChunkWords = int64_t{1} << 14;
constexpr uint64_t kAll = ~uint64_t{0};

// The outside bits of the eight states from `s` on, as the low byte.
uint64_t OutsideBits8(const VoxelState* s) {
  const uint64_t outside = (LoadStates8(s) >> 7) & kLowBits8;  // 1 in each outside state's byte
  return (outside * 0x0102040810204080ull) >> 56;              // byte k's low bit to bit k
}

// The words of a bitset as a filter pass reads them: a word before the first or after the
// last reads `beyond`, and so do the bits past the last voxel.
class WordReader {
 public:
  WordReader(const FlatBitset& bits, uint64_t beyond)
      : words_(bits.words()), count_(static_cast<int64_t>(bits.word_count())), beyond_(beyond) {
    const int tail = static_cast<int>(bits.bits() & 63);
    last_valid_ = tail == 0 ? kAll : (uint64_t{1} << tail) - 1;
  }
  int64_t count() const { return count_; }
  uint64_t Word(int64_t q) const {
    if (q < 0 || q >= count_) return beyond_;
    if (q == count_ - 1) return (words_[q] & last_valid_) | (beyond_ & ~last_valid_);
    return words_[q];
  }
  // Bit k of word w moved by `shift` voxels: voxel 64 w + k + shift's bit.
  uint64_t Shifted(int64_t w, int64_t shift) const {
    const int64_t pos = w * 64 + shift;
    const int64_t q = pos >> 6;  // floor, for negative positions too
    const int r = static_cast<int>(pos & 63);
    const uint64_t lo = Word(q);
    return r == 0 ? lo : (lo >> r) | (Word(q + 1) << (64 - r));
  }
  const uint64_t* words() const { return words_; }
  uint64_t last_valid() const { return last_valid_; }

 private:
  const uint64_t* words_;
  int64_t count_;
  uint64_t beyond_;
  uint64_t last_valid_;
};

// to := from combined with itself moved by -stride and +stride (AND or OR).
void FilterPass(const FlatBitset& from, FlatBitset& to, int64_t stride, bool erode,
                int threads) {
  const WordReader in(from, erode ? kAll : 0);
  uint64_t* const out = to.words();
  const int64_t words = in.count();
  // Words whose reads all fall inside the array's words but the last: no test per read.
  const int64_t reach = (stride + 63) / 64 + 1;
  const int64_t fast_lo = reach, fast_hi = words - 1 - reach;  // [fast_lo, fast_hi)
  const int64_t whole = stride >> 6;
  const int r = static_cast<int>(stride & 63);
  RunTasks(threads, (words + kChunkWords - 1) / kChunkWords, [&](int, int64_t task) {
    const int64_t begin = task * kChunkWords, end = std::min(words, begin + kChunkWords);
    const uint64_t* const w = in.words();
    for (int64_t i = begin; i < end; ++i) {
      uint64_t below, above;
      if (i >= fast_lo && i < fast_hi) {
        // Voxel 64 i + k - stride and + stride.
        const int64_t qb = i - whole, qa = i + whole;
        below = r == 0 ? w[qb] : (w[qb - 1] >> (64 - r)) | (w[qb] << r);
        above = r == 0 ? w[qa] : (w[qa] >> r) | (w[qa + 1] << (64 - r));
        out[i] = erode ? (below & w[i] & above) : (below | w[i] | above);
      } else {
        below = in.Shifted(i, -stride);
        above = in.Shifted(i, stride);
        const uint64_t mid = in.Word(i);
        out[i] = erode ? (below & mid & above) : (below | mid | above);
      }
    }
    if (end == words && words > 0) out[words - 1] &= in.last_valid();
  });
}

}  // namespace

FlatBitset OutsideBits(const VoxelGrid& grid, int threads) {
  const int64_t count = grid.size();
  const int64_t words = (count + 63) / 64;
  // Every word is written below: unset, so that the threads take the fresh pages' faults (a
  // zeroed bitset is a serial pass over 270 MB on a 10M-point cloud's grid).
  FlatBitset bits(count, nullptr, FlatBitset::Unset{});
  uint64_t* const out = bits.words();
  const VoxelState* const s = grid.states().data();
  RunTasks(threads, (words + kChunkWords - 1) / kChunkWords, [=](int, int64_t task) {
    const int64_t end = std::min(words, (task + 1) * kChunkWords);
    for (int64_t w = task * kChunkWords; w < end; ++w) {
      const int64_t base = w * 64;
      uint64_t word = 0;
      if (base + 64 <= count) {
        for (int k = 0; k < 8; ++k) word |= OutsideBits8(s + base + 8 * k) << (8 * k);
      } else {
        for (int64_t i = base; i < count; ++i) word |= uint64_t{IsOutside(s[i])} << (i - base);
      }
      out[w] = word;
    }
  });
  return bits;
}

void BoxFilterBits(const std::array<int, 3>& dims, bool erode, FlatBitset& bits,
                   FlatBitset& scratch, int threads) {
  const int64_t strides[3] = {1, dims[0], int64_t{dims[0]} * dims[1]};
  FilterPass(bits, scratch, strides[0], erode, threads);
  FilterPass(scratch, bits, strides[1], erode, threads);
  FilterPass(bits, scratch, strides[2], erode, threads);
  std::swap(bits, scratch);
}

}  // namespace membrane

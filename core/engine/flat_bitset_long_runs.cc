// Erosion and dilation by long runs in passes that do not grow with the run.
//
// The doubling runs of flat_bitset.cc take ceil(log2 n) + 1 passes over the set: 11 for the
// plates of 646 voxels of a 10M-point cloud, where each pass reads and writes 271 MB. Here a
// run along x is one pass (the lengths of runs of ones carried from word to word), and a run
// along a stride s >= 129 is three (van Herk / Gil-Werman: the cells along the stride cut into
// blocks of n, an AND from each block's start, one to its end, and one pass joining them).
// Both give the doubling's bits, including bits read past the ends (zero), and are used for
// the runs where they are faster (kLongAlongX, LongRun).
#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/base/parallel_tasks.h"
#include "core/engine/flat_bitset.h"
#include "core/engine/ivdep.h"
#include "core/engine/word_blocks.h"

namespace membrane {
namespace {

// Bits a..b of a word, 0 <= a <= b <= 63.
uint64_t BitRange(int a, int b) { return (~0ull >> (63 - b)) & (~0ull << a); }

// Bits i of x with x[i .. i + n - 1] all set inside the word (1 <= n <= 64).
uint64_t ErodeUpInWord(uint64_t x, int n) {
  int len = 1;
  for (; 2 * len <= n; len *= 2) x &= x >> len;
  if (len < n) x &= x >> (n - len);
  return x;
}

// Bits i of x with x[i - n + 1 .. i] all set inside the word (1 <= n <= 64).
uint64_t ErodeDownInWord(uint64_t x, int n) {
  int len = 1;
  for (; 2 * len <= n; len *= 2) x &= x << len;
  if (len < n) x &= x << (n - len);
  return x;
}

// dst[i] = AND_{j<n} src[i + j] for the words [begin, end), descending: `ones_above` counts the
// set bits from bit 0 of the word above upwards (capped at n), so a word's top run of ones
// knows how far it goes; it starts as OnesFrom(src, words, end, n).
void ErodeAlongX(const uint64_t* src, uint64_t* dst, int64_t begin, int64_t end, int n,
                 int64_t ones_above) {
  for (int64_t w = end - 1; w >= begin; --w) {
    const uint64_t x = src[w];
    const uint64_t zeros = ~x;
    uint64_t r = n <= 64 ? ErodeUpInWord(x, n) : 0;
    // The top run of ones, bits t0..63: bit i's run is 64 - i + ones_above long.
    const int t0 = zeros == 0 ? 0 : 64 - __builtin_clzll(zeros);
    const int64_t highest = std::min<int64_t>(63, 64 + ones_above - n);
    if (t0 < 64 && highest >= t0) r |= BitRange(t0, static_cast<int>(highest));
    ones_above = zeros == 0 ? std::min<int64_t>(64 + ones_above, n) : __builtin_ctzll(zeros);
    dst[w] = r;
  }
}

// The set bits of src from bit 0 of word w upwards, capped at n (past the end: zeros).
int64_t OnesFrom(const uint64_t* src, int64_t words, int64_t w, int n) {
  int64_t ones = 0;
  for (; w < words && ones < n; ++w) {
    if (~src[w] != 0) return std::min<int64_t>(ones + __builtin_ctzll(~src[w]), n);
    ones += 64;
  }
  return std::min<int64_t>(ones, n);
}

// dst[i] = OR_{j<n} src[i - j] for the words [begin, end), ascending: the complement of the
// erosion, downwards, of the zeros; `zeros_below` counts the zeros from bit 63 of the word
// below downwards (capped at n); it starts as ZerosBelow(src, begin, n).
void DilateAlongX(const uint64_t* src, uint64_t* dst, int64_t begin, int64_t end, int n,
                  int64_t zeros_below) {
  for (int64_t w = begin; w < end; ++w) {
    const uint64_t x = src[w];
    uint64_t no_one = n <= 64 ? ErodeDownInWord(~x, n) : 0;
    // The bottom run of zeros, bits 0..b0-1: bit i's run is i + 1 + zeros_below long.
    const int b0 = x == 0 ? 64 : __builtin_ctzll(x);
    const int64_t lowest = std::max<int64_t>(0, n - 1 - zeros_below);
    if (b0 > 0 && lowest <= b0 - 1) no_one |= BitRange(static_cast<int>(lowest), b0 - 1);
    zeros_below = x == 0 ? std::min<int64_t>(64 + zeros_below, n) : __builtin_clzll(x);
    dst[w] = ~no_one;
  }
}

// The zeros of src from bit 63 of word w - 1 downwards, capped at n (before the start: zeros).
int64_t ZerosBelow(const uint64_t* src, int64_t w, int n) {
  int64_t zeros = 0;
  for (--w; w >= 0 && zeros < n; --w) {
    if (src[w] != 0) return std::min<int64_t>(zeros + __builtin_clzll(src[w]), n);
    zeros += 64;
  }
  return n;
}

// The runs along x on `threads`: blocks of words, each starting from its count of the bits
// beyond it, all counted before any block is written (src may be dst).
template <bool kErode>
void RunAlongX(int threads, const uint64_t* src, uint64_t* dst, int64_t words, int n) {
  const int64_t blocks = WordBlockCount(threads, words);
  std::vector<int64_t> start(static_cast<size_t>(blocks));
  for (int64_t b = 0; b < blocks; ++b) {
    const int64_t begin = b * kWordBlock, end = std::min(words, begin + kWordBlock);
    start[static_cast<size_t>(b)] = kErode ? OnesFrom(src, words, end, n) : ZerosBelow(src, begin, n);
  }
  ForWordBlocks(threads, words, [&](int64_t b, int64_t begin, int64_t end) {
    if constexpr (kErode) {
      ErodeAlongX(src, dst, begin, end, n, start[static_cast<size_t>(b)]);
    } else {
      DilateAlongX(src, dst, begin, end, n, start[static_cast<size_t>(b)]);
    }
  });
}

// The 64 bits of `a` (of `words` words) from bit position 64 * w + k, zeros outside.
class ShiftedReader {
 public:
  ShiftedReader(const uint64_t* a, int64_t words, int64_t k)
      : a_(a), words_(words), q_(k >= 0 ? k / 64 : -((-k + 63) / 64)),
        r_(static_cast<int>(k - q_ * 64)) {}
  // Checked: words outside the set read as 0.
  uint64_t operator()(int64_t w) const {
    const int64_t i = w + q_;
    const uint64_t lo = i >= 0 && i < words_ ? a_[i] : 0;
    const uint64_t hi = i + 1 >= 0 && i + 1 < words_ ? a_[i + 1] : 0;
    return Join(lo, hi);
  }
  // Unchecked, for w in [safe_begin(), safe_end()).
  uint64_t Raw(int64_t w) const { return Join(a_[w + q_], a_[w + q_ + 1]); }
  int64_t safe_begin() const { return std::max<int64_t>(0, -q_); }
  int64_t safe_end() const { return std::min<int64_t>(words_, words_ - q_ - 1); }

 private:
  // (hi << 1) << (63 - r) is hi << (64 - r), and 0 for r = 0, without a shift by 64.
  uint64_t Join(uint64_t lo, uint64_t hi) const { return (lo >> r_) | ((hi << 1) << (63 - r_)); }

  const uint64_t* a_;
  int64_t words_;
  int64_t q_;
  int r_;
};

// The cells along stride s form chains i, i + s, i + 2s, ...; bit i is cell floor(i / s) of
// its chain, and blocks are n consecutive cells from cell 0. One pass over the words, cell by
// cell (ascending or descending), sets
//   dst[i] = src[i]                                     where cell(i) = `edge` modulo n,
//   dst[i] = src[i] & tap[i + k]  (kAnd; | otherwise)   elsewhere,
// tap read past the ends as 0. With s >= 129 a word's tap words are at least two words away
// from it, on the side the pass has finished (k = -s ascending, k = s descending), so the
// loop over a cell's whole words is free to vectorize. At most one word per cell holds two
// cells; it gets a mask.
template <bool kAnd, bool kAscending>
void CellPass(const uint64_t* src, uint64_t* dst, const uint64_t* tap, int64_t words, int64_t s,
              int n, int edge, int64_t k) {
  const ShiftedReader reader(tap, words, k);
  const int64_t lo_safe = reader.safe_begin(), hi_safe = reader.safe_end();
  auto combine = [](uint64_t x, uint64_t keep, uint64_t t) {
    return kAnd ? x & (keep | t) : x | (~keep & t);
  };
  // Words [b, e) all in one cell: `keep` all ones on the edge cells, else zero.
  auto whole = [&](int64_t b, int64_t e, bool on_edge) {
    if (on_edge) {
      std::copy(src + b, src + e, dst + b);
      return;
    }
    const int64_t sb = std::clamp(lo_safe, b, e), se = std::clamp(hi_safe, sb, e);
    if constexpr (kAscending) {
      for (int64_t w = b; w < sb; ++w) dst[w] = combine(src[w], 0, reader(w));
      MEMBRANE_IVDEP
      for (int64_t w = sb; w < se; ++w) dst[w] = combine(src[w], 0, reader.Raw(w));
      for (int64_t w = se; w < e; ++w) dst[w] = combine(src[w], 0, reader(w));
    } else {
      for (int64_t w = e - 1; w >= se; --w) dst[w] = combine(src[w], 0, reader(w));
      MEMBRANE_IVDEP
      for (int64_t w = se - 1; w >= sb; --w) dst[w] = combine(src[w], 0, reader.Raw(w));
      for (int64_t w = sb - 1; w >= b; --w) dst[w] = combine(src[w], 0, reader(w));
    }
  };
  // The word holding the first bit of cell c (when it is not a word's first bit): its low
  // bits are in cell c - 1.
  auto split = [&](int64_t c, int phase) {
    const int64_t first = c * s;
    const uint64_t low = (1ull << (first % 64)) - 1;
    const int previous = phase == 0 ? n - 1 : phase - 1;
    const uint64_t keep = (previous == edge ? low : 0) | (phase == edge ? ~low : 0);
    const int64_t w = first / 64;
    dst[w] = combine(src[w], keep, reader(w));
  };
  const int64_t bits = words * 64;
  const int64_t cells = (bits + s - 1) / s;
  if constexpr (kAscending) {
    for (int64_t c = 0, phase = 0; c < cells; ++c, phase = phase + 1 == n ? 0 : phase + 1) {
      const int64_t first = c * s;
      int64_t b = (first + 63) / 64;
      if (first % 64 != 0) split(c, static_cast<int>(phase));
      whole(b, std::min(words, (first + s) / 64), phase == edge);
    }
  } else {
    for (int64_t c = cells - 1, phase = c % n; c >= 0; --c, phase = phase == 0 ? n - 1 : phase - 1) {
      const int64_t first = c * s;
      whole((first + 63) / 64, std::min(words, (first + s) / 64), phase == edge);
      if (first % 64 != 0) split(c, static_cast<int>(phase));
    }
  }
}

// Stride s >= 129, n >= 2. Erosion: `from_start` gets the AND from each block's start to the
// cell, `this` first the AND from the cell to its block's end, then the result (the window
// from cell c covers the end of c's block and the start of the next one). Dilation mirrors
// it with ORs: `to_end` the OR to the block's end, `this` the OR from its start, then the
// window from cell c - n + 1 to c.
//
// Each cell pass runs along whole chains, so it stays on one thread; but when src is not dst's
// own words the two passes read only src and write only their own planes, and they run side
// by side (two tasks, the same words as one after the other). In place, the second pass
// overwrites the src the first one reads: one after the other.
template <typename First, typename Second>
void TwoCellPasses(const uint64_t* src, const FlatBitset& dst, const First& first,
                   const Second& second) {
  if (dst.threads() > 1 && src != dst.words()) {
    RunTasks(2, 2, [&](int, int64_t task) {
      if (task == 0) {
        first();
      } else {
        second();
      }
    });
    return;
  }
  first();
  second();
}

void ErodeBlocks(const uint64_t* src, FlatBitset& dst, FlatBitset& from_start, int n, int64_t s) {
  const int64_t words = static_cast<int64_t>(dst.word_count());
  TwoCellPasses(
      src, dst,
      [&] { CellPass<true, true>(src, from_start.words(), from_start.words(), words, s, n, 0, -s); },
      [&] { CellPass<true, false>(src, dst.words(), dst.words(), words, s, n, n - 1, s); });
  dst.AndShifted(from_start, -(n - 1) * s);
}

void DilateBlocks(const uint64_t* src, FlatBitset& dst, FlatBitset& to_end, int n, int64_t s) {
  const int64_t words = static_cast<int64_t>(dst.word_count());
  TwoCellPasses(
      src, dst,
      [&] { CellPass<false, false>(src, to_end.words(), to_end.words(), words, s, n, n - 1, s); },
      [&] { CellPass<false, true>(src, dst.words(), dst.words(), words, s, n, 0, -s); });
  dst.OrShifted(to_end, (n - 1) * s);
}

// Along x the one pass does more work per word than a vectorized doubling pass: it pays from
// runs of 64 (7 doubling passes). The blocks' three passes pay from runs of 17 (five doubling
// passes; at 9-16, four, they were no faster), along strides of 129 and more (CellPass).
constexpr int kLongAlongX = 64;

// The run of n along `stride` from src into dst (src may be dst's words) when one of the
// long-run methods pays; false (nothing written) when the doubling should run instead.
template <bool kErode>
bool LongRun(const uint64_t* src, FlatBitset& dst, int n, int64_t stride, FlatBitset& scratch) {
  const int64_t words = static_cast<int64_t>(dst.word_count());
  if (stride == 1 && n >= kLongAlongX) {
    RunAlongX<kErode>(dst.threads(), src, dst.words(), words, n);
    return true;
  }
  if (stride < 129 || n <= 16) return false;
  if constexpr (kErode) {
    ErodeBlocks(src, dst, scratch, n, stride);
  } else {
    DilateBlocks(src, dst, scratch, n, stride);
  }
  return true;
}

}  // namespace

void FlatBitset::ErodeRun(int n, int64_t stride, FlatBitset& scratch) {
  if (!LongRun<true>(words_.data(), *this, n, stride, scratch)) ErodeRun(n, stride);
}

void FlatBitset::DilateRun(int n, int64_t stride, FlatBitset& scratch) {
  if (!LongRun<false>(words_.data(), *this, n, stride, scratch)) DilateRun(n, stride);
}

void FlatBitset::ErodeRunFrom(const FlatBitset& src, int n, int64_t stride,
                              FlatBitset& scratch) {
  if (!LongRun<true>(src.words(), *this, n, stride, scratch)) ErodeRunFrom(src, n, stride);
}

void FlatBitset::DilateRunFrom(const FlatBitset& src, int n, int64_t stride,
                               FlatBitset& scratch) {
  if (!LongRun<false>(src.words(), *this, n, stride, scratch)) DilateRunFrom(src, n, stride);
}

}  // namespace membrane

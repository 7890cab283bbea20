#include "core/engine/flat_bitset.h"

#include <algorithm>
#include <vector>

#include "core/base/parallel_tasks.h"
#include "core/engine/ivdep.h"
#include "core/engine/rewritten_buffer.h"
#include "core/engine/word_blocks.h"

namespace membrane {

FlatBitset& FlatBitset::operator=(const FlatBitset& o) {
  if (this == &o) return *this;
  if (bits_ != o.bits_) {
    bits_ = o.bits_;
    threads_ = o.threads_;
    words_ = o.words_;
    return *this;
  }
  const uint64_t* from = o.words_.data();
  uint64_t* to = words_.data();
  ForWordBlocks(threads_, static_cast<int64_t>(words_.size()),
                [&](int64_t, int64_t b, int64_t e) { std::copy(from + b, from + e, to + b); });
  return *this;
}

void FlatBitset::clear_all() {
  uint64_t* w = words_.data();
  ForWordBlocks(threads_, static_cast<int64_t>(words_.size()),
                [&](int64_t, int64_t b, int64_t e) { std::fill(w + b, w + e, 0); });
}

bool FlatBitset::any() const {
  return std::any_of(words_.begin(), words_.end(), [](uint64_t w) { return w != 0; });
}

// The element-wise passes: each block of words on its own.
void FlatBitset::And(const FlatBitset& o) {
  uint64_t* w = words_.data();
  const uint64_t* x = o.words_.data();
  ForWordBlocks(threads_, static_cast<int64_t>(words_.size()), [&](int64_t, int64_t b, int64_t e) {
    for (int64_t i = b; i < e; ++i) w[i] &= x[i];
  });
}
void FlatBitset::Or(const FlatBitset& o) {
  uint64_t* w = words_.data();
  const uint64_t* x = o.words_.data();
  ForWordBlocks(threads_, static_cast<int64_t>(words_.size()), [&](int64_t, int64_t b, int64_t e) {
    for (int64_t i = b; i < e; ++i) w[i] |= x[i];
  });
}
void FlatBitset::AndNot(const FlatBitset& o) {
  uint64_t* w = words_.data();
  const uint64_t* x = o.words_.data();
  ForWordBlocks(threads_, static_cast<int64_t>(words_.size()), [&](int64_t, int64_t b, int64_t e) {
    for (int64_t i = b; i < e; ++i) w[i] &= ~x[i];
  });
}

bool FlatBitset::OrChanged(const FlatBitset& o) {
  const int64_t n = static_cast<int64_t>(words_.size());
  std::vector<uint64_t> added(static_cast<size_t>(WordBlockCount(threads_, n)), 0);
  uint64_t* w = words_.data();
  const uint64_t* x = o.words_.data();
  ForWordBlocks(threads_, n, [&](int64_t block, int64_t b, int64_t e) {
    uint64_t a = 0;
    for (int64_t i = b; i < e; ++i) {
      a |= x[i] & ~w[i];
      w[i] |= x[i];
    }
    added[static_cast<size_t>(block)] = a;
  });
  return std::any_of(added.begin(), added.end(), [](uint64_t a) { return a != 0; });
}

uint64_t FlatBitset::WordAt(int64_t pos) const {
  const int64_t n = static_cast<int64_t>(words_.size());
  // Floor division so that negative positions work.
  const int64_t q = pos >= 0 ? pos >> 6 : -((-pos + 63) >> 6);
  const int r = static_cast<int>(pos - q * 64);
  const uint64_t lo = (q >= 0 && q < n) ? words_[static_cast<size_t>(q)] : 0;
  if (r == 0) return lo;
  const uint64_t hi = (q + 1 >= 0 && q + 1 < n) ? words_[static_cast<size_t>(q + 1)] : 0;
  return (lo >> r) | (hi << (64 - r));
}

namespace {

// The in-place shifted passes on threads: segments of at least 16 times the words a word reads
// away from itself, so that saving the words each segment reads from its neighbour before the
// pass (the halo) costs at most a sixteenth of it.
int64_t HaloSegmentWords(int64_t q) { return std::max<int64_t>(kWordBlock, 16 * (q + 2)); }

// `halo` with room for `words` words: kept from pass to pass, since fresh pages for every pass
// would cost more than the copy; one that must grow takes exactly `words`.
std::vector<uint64_t>& HaloOf(std::vector<uint64_t>& halo, int64_t words) {
  if (static_cast<int64_t>(halo.size()) < words) ResizeRewritten(halo, static_cast<size_t>(words));
  return halo;
}

// w[i] &= (the old words from bit 64 i + 64 q + r), i ascending in [begin, end) of n words:
// old words before `end` are read in place (not yet written: i ascends and reads at or above
// itself), from `end` on through halo[m - end], past n as 0.
void AndShiftedDownRange(uint64_t* w, int64_t n, int64_t q, int r, int64_t begin, int64_t end,
                         const uint64_t* halo) {
  // The main loop has no bounds checks (this and OrShiftedUpRange are most of the word
  // operations of a shrink).
  const int64_t main_end = std::max(begin, std::min(end, n) - q - 1);
  if (r == 0) {
    for (int64_t i = begin; i < main_end; ++i) w[i] &= w[i + q];
  } else {
    for (int64_t i = begin; i < main_end; ++i) w[i] &= (w[i + q] >> r) | (w[i + q + 1] << (64 - r));
  }
  auto old = [&](int64_t m) -> uint64_t {
    if (m < end) return w[m];
    return m < n ? halo[m - end] : 0;
  };
  for (int64_t i = main_end; i < end; ++i) {
    const uint64_t lo = old(i + q);
    const uint64_t hi = r != 0 ? old(i + q + 1) : 0;
    w[i] &= r == 0 ? lo : (lo >> r) | (hi << (64 - r));
  }
}

// w[i] |= (the old words from bit 64 i - 64 q - r), i descending in [begin, end): old words at
// or above `begin` in place, below it through halo[m - (begin - q - 1)], before 0 as 0.
void OrShiftedUpRange(uint64_t* w, int64_t q, int r, int64_t begin, int64_t end,
                      const uint64_t* halo) {
  const int64_t main_begin = std::min(end, begin + q + 1);  // i - q - 1 >= begin from here
  // Every read is at or below the word written and every earlier write above it, so loading
  // a block of sources before storing its words is exact: ivdep lets GCC vectorize the
  // descending loop, which it would not on its own.
  if (r == 0) {
MEMBRANE_IVDEP
    for (int64_t i = end - 1; i >= main_begin; --i) w[i] |= w[i - q];
  } else {
MEMBRANE_IVDEP
    for (int64_t i = end - 1; i >= main_begin; --i) {
      w[i] |= (w[i - q] << r) | (w[i - q - 1] >> (64 - r));
    }
  }
  auto old = [&](int64_t m) -> uint64_t {
    if (m >= begin) return w[m];
    return m >= 0 ? halo[m - (begin - q - 1)] : 0;
  };
  for (int64_t i = main_begin - 1; i >= begin; --i) {
    const uint64_t hi = old(i - q);
    const uint64_t lo = r != 0 ? old(i - q - 1) : 0;
    w[i] |= r == 0 ? hi : (hi << r) | (lo >> (64 - r));
  }
}

// Runs range(begin, end, halo) over all n words of `w`, in segments on `threads` threads when
// there are several: each segment's range reads the q + 1 words beside it, after it
// (`halo_after`) or before it, as they were before any segment wrote them, so those are saved
// into `store` first (range's `halo`: null when the whole runs as one).
template <typename Range>
void RunInHaloSegments(int threads, std::vector<uint64_t>& store, uint64_t* w, int64_t n,
                       int64_t q, bool halo_after, const Range& range) {
  const int64_t seg = HaloSegmentWords(q);
  const int64_t segments = (n + seg - 1) / seg;
  if (threads <= 1 || segments < 2) {
    range(0, n, nullptr);
    return;
  }
  const int64_t h = q + 1;
  std::vector<uint64_t>& halo = HaloOf(store, segments * h);
  // Task t saves the words between segments t and t + 1: the head of t + 1 for segment t, or
  // the tail of t for segment t + 1 (placed at the end of its h words when t is short).
  RunTasks(threads, segments - 1, [&](int, int64_t t) {
    const int64_t seam = (t + 1) * seg;
    if (halo_after) {
      std::copy(w + seam, w + std::min(n, seam + h), halo.data() + t * h);
    } else {
      const int64_t from = std::max<int64_t>(0, seam - h);
      std::copy(w + from, w + seam, halo.data() + (t + 1) * h + (from - (seam - h)));
    }
  });
  RunTasks(threads, segments, [&](int, int64_t j) {
    range(j * seg, std::min(n, (j + 1) * seg), halo.data() + j * h);
  });
}

}  // namespace

void FlatBitset::AndShiftedDown(int64_t k) {
  const int64_t n = static_cast<int64_t>(words_.size());
  const int64_t q = k >> 6;
  const int r = static_cast<int>(k & 63);
  uint64_t* w = words_.data();
  RunInHaloSegments(threads_, halo(), w, n, q, /*halo_after=*/true,
                    [&](int64_t begin, int64_t end, const uint64_t* halo) {
                      AndShiftedDownRange(w, n, q, r, begin, end, halo);
                    });
}

void FlatBitset::OrShiftedUp(int64_t k) {
  const int64_t n = static_cast<int64_t>(words_.size());
  const int64_t q = k >> 6;
  const int r = static_cast<int>(k & 63);
  uint64_t* w = words_.data();
  RunInHaloSegments(threads_, halo(), w, n, q, /*halo_after=*/false,
                    [&](int64_t begin, int64_t end, const uint64_t* halo) {
                      OrShiftedUpRange(w, q, r, begin, end, halo);
                    });
}

namespace {

// Applies dst[w] = op(base[w], the 64 bits of src starting at bit w * 64 - k) to the words w
// in [begin, end), with the word offset and bit shift computed once (bits outside src read as
// 0). `base` is dst itself for the in-place operations.
template <typename Op>
void CombineShiftedRange(uint64_t* dst, const uint64_t* base, const uint64_t* src, int64_t words,
                         int64_t k, Op op, int64_t begin, int64_t end) {
  const int64_t off = -k;
  const int64_t q = off >= 0 ? off / 64 : -((-off + 63) / 64);
  const int r = static_cast<int>(off - q * 64);
  auto get = [&](int64_t w) {
    const int64_t a = w + q;
    const uint64_t x = (a >= 0 && a < words) ? src[a] : 0;
    if (r == 0) return x;
    const uint64_t y = (a + 1 >= 0 && a + 1 < words) ? src[a + 1] : 0;
    return (x >> r) | (y << (64 - r));
  };
  // Words whose sources a = w + q and a + 1 both lie in [0, words) need no checks.
  const int64_t first = std::clamp<int64_t>(-q, begin, end);
  const int64_t last = std::clamp<int64_t>(words - q - 1, first, end);
  int64_t w = begin;
  for (; w < first; ++w) dst[w] = op(base[w], get(w));
  if (r == 0) {
    for (; w < last; ++w) dst[w] = op(base[w], src[w + q]);
  } else {
    for (; w < last; ++w) dst[w] = op(base[w], (src[w + q] >> r) | (src[w + q + 1] << (64 - r)));
  }
  for (; w < end; ++w) dst[w] = op(base[w], get(w));
}

// The same over every word, in blocks on `threads` threads when dst is not src (in place,
// the words read may already be written, so the pass stays on the calling thread, in order).
template <typename Op>
void CombineShifted(int threads, uint64_t* dst, const uint64_t* base, const uint64_t* src,
                    int64_t words, int64_t k, Op op) {
  ForWordBlocks(dst == src ? 1 : threads, words, [&](int64_t, int64_t b, int64_t e) {
    CombineShiftedRange(dst, base, src, words, k, op, b, e);
  });
}

uint64_t ReverseBits(uint64_t x) {
  x = ((x >> 1) & 0x5555555555555555ull) | ((x & 0x5555555555555555ull) << 1);
  x = ((x >> 2) & 0x3333333333333333ull) | ((x & 0x3333333333333333ull) << 2);
  x = ((x >> 4) & 0x0f0f0f0f0f0f0f0full) | ((x & 0x0f0f0f0f0f0f0f0full) << 4);
  return __builtin_bswap64(x);
}

// Within one word, the bits of `run` from each run's lowest seed upwards, `seed` a subset of
// `run`: adding a seed bit carries through the ones above it up to the end of its run and
// clears them; seeds above the lowest one in a run are set again by the addition itself.
uint64_t FillUp(uint64_t run, uint64_t seed) { return (run & ~(run + seed)) | seed; }

}  // namespace

void FlatBitset::AssignShifted(const FlatBitset& other, int64_t k) {
  CombineShifted(threads_, words_.data(), words_.data(), other.words_.data(),
                 static_cast<int64_t>(words_.size()), k,
                 [](uint64_t, uint64_t b) { return b; });
}

void FlatBitset::OrShifted(const FlatBitset& other, int64_t k) {
  CombineShifted(threads_, words_.data(), words_.data(), other.words_.data(),
                 static_cast<int64_t>(words_.size()), k,
                 [](uint64_t a, uint64_t b) { return a | b; });
}

void FlatBitset::AndShifted(const FlatBitset& other, int64_t k) {
  CombineShifted(threads_, words_.data(), words_.data(), other.words_.data(),
                 static_cast<int64_t>(words_.size()), k,
                 [](uint64_t a, uint64_t b) { return a & b; });
}

void FlatBitset::AssignAndShifted(const FlatBitset& a, const FlatBitset& b, int64_t k) {
  CombineShifted(threads_, words_.data(), a.words_.data(), b.words_.data(),
                 static_cast<int64_t>(words_.size()), k,
                 [](uint64_t x, uint64_t y) { return x & y; });
}

void FlatBitset::AssignOr(const FlatBitset& a, const FlatBitset& b) {
  uint64_t* w = words_.data();
  const uint64_t *x = a.words_.data(), *y = b.words_.data();
  ForWordBlocks(threads_, static_cast<int64_t>(words_.size()), [&](int64_t, int64_t lo, int64_t hi) {
    for (int64_t i = lo; i < hi; ++i) w[i] = x[i] | y[i];
  });
}

void FlatBitset::AssignOrAnd(const FlatBitset& a, const FlatBitset& b, const FlatBitset& c) {
  uint64_t* w = words_.data();
  const uint64_t *x = a.words_.data(), *y = b.words_.data(), *z = c.words_.data();
  ForWordBlocks(threads_, static_cast<int64_t>(words_.size()), [&](int64_t, int64_t lo, int64_t hi) {
    for (int64_t i = lo; i < hi; ++i) w[i] = (x[i] | y[i]) & z[i];
  });
}

namespace {

// The one-pass spreads on threads: segments spread on their own (reading nothing before a
// segment for a positive step, nothing after it for a negative one), then, in order, each
// segment is passed again from its seam with its neighbour's final words until a word's inputs
// are as they were. Exact (a segment's own spread is a subset of the final bits holding every
// seed, and the pass again from the final neighbour makes it the final bits). A spread reaches
// at most max_len cells, so the pass from a seam stops within a chain of max_len * |step|
// bits: segments of at least eight chains keep it under an eighth of the work. Along z, where
// a chain is the whole plane, that leaves one segment: the calling thread.
int64_t SpreadSegmentWords(int64_t q, int64_t max_len, int64_t mag) {
  const int64_t chain_words = max_len * mag / 64 + 1;
  return std::max({2 * kWordBlock, 64 * (q + 2), 8 * chain_words});
}

// Along a stride of 64 bits or more, positive step, words [begin, end): bits read from words
// before `floor` count as 0. `stop` (the pass from a seam): returns at the first word whose
// inputs are all as they were when the segment was spread on its own.
void SpreadUpRange(uint64_t* w, const uint64_t* run_w, int64_t q, int r, int64_t begin,
                   int64_t end, int64_t floor, bool stop) {
  int64_t last_change = begin - 1;
  for (int64_t k = std::max(begin, q); k < end; ++k) {
    if (stop && k >= begin + q + 1 && last_change < k - q - 1) return;
    const int64_t h = k - q, l = k - q - 1;
    const uint64_t hi = h >= floor ? w[h] : 0;
    const uint64_t lo = l >= floor && l >= 0 ? w[l] : 0;
    const uint64_t src = r == 0 ? hi : (hi << r) | (lo >> (64 - r));
    const uint64_t next = w[k] | (run_w[k] & src);
    if (next != w[k]) last_change = k;
    w[k] = next;
  }
}

// The mirror: negative step, words (begin, end] taken downwards from end - 1; bits read from
// words at or after `ceiling` count as 0.
void SpreadDownRange(uint64_t* w, const uint64_t* run_w, int64_t n, int64_t q, int r,
                     int64_t begin, int64_t end, int64_t ceiling, bool stop) {
  int64_t last_change = end;
  for (int64_t k = std::min(end, n - q) - 1; k >= begin; --k) {
    if (stop && k <= end - 1 - q - 1 && last_change > k + q + 1) return;
    const int64_t l = k + q, h = k + q + 1;
    const uint64_t lo = l < ceiling ? w[l] : 0;
    const uint64_t hi = h < ceiling && h < n ? w[h] : 0;
    const uint64_t src = r == 0 ? lo : (lo >> r) | (hi << (64 - r));
    const uint64_t next = w[k] | (run_w[k] & src);
    if (next != w[k]) last_change = k;
    w[k] = next;
  }
}

// Along x, upwards: the top result bit of a word seeds the next word. `stop`: returns at the
// first word the pass leaves unchanged (its carry is then the one the next word had).
void FillUpRange(uint64_t* w, const uint64_t* run_w, int64_t begin, int64_t end, uint64_t carry,
                 bool stop) {
  for (int64_t k = begin; k < end; ++k) {
    const uint64_t r = run_w[k];
    const uint64_t next = FillUp(r, w[k] | (carry & r & 1));
    const bool same = next == w[k];
    w[k] = next;
    carry = next >> 63;
    if (stop && same) return;
  }
}

// Along x, downwards: upwards in bit-reversed words, taken from the highest word down.
void FillDownRange(uint64_t* w, const uint64_t* run_w, int64_t begin, int64_t end,
                   uint64_t carry, bool stop) {
  for (int64_t k = end - 1; k >= begin; --k) {
    const uint64_t r = ReverseBits(run_w[k]);
    const uint64_t filled = FillUp(r, ReverseBits(w[k]) | (carry & r & 1));
    const uint64_t next = ReverseBits(filled);
    const bool same = next == w[k];
    w[k] = next;
    carry = filled >> 63;
    if (stop && same) return;
  }
}

}  // namespace

void FlatBitset::SpreadAlong(const FlatBitset& run, int64_t step, int64_t max_len,
                             FlatBitset& scratch_a, FlatBitset& scratch_b) {
  const int64_t n = static_cast<int64_t>(words_.size());
  const int64_t mag = step < 0 ? -step : step;
  if (mag >= 64 || mag == 1) {
    // Every source bit of word w lies in an earlier word in the order of the step (along x:
    // the carry of the word before): one pass, or segments on threads.
    const int64_t q = mag >= 64 ? mag / 64 : 0;
    const int r = static_cast<int>(mag % 64);
    const uint64_t* run_w = run.words_.data();
    uint64_t* w = words_.data();
    const int64_t seg = SpreadSegmentWords(q, max_len, mag);
    const int64_t segments = (n + seg - 1) / seg;
    const bool split = threads_ > 1 && segments >= 2;
    auto pass = [&](int64_t begin, int64_t end, bool from_seam) {
      if (mag == 1) {
        if (step > 0) {
          FillUpRange(w, run_w, begin, end, from_seam ? w[begin - 1] >> 63 : 0, from_seam);
        } else {
          FillDownRange(w, run_w, begin, end, from_seam ? w[end] & 1 : 0, from_seam);
        }
      } else if (step > 0) {
        SpreadUpRange(w, run_w, q, r, begin, end, from_seam ? 0 : begin, from_seam);
      } else {
        SpreadDownRange(w, run_w, n, q, r, begin, end, from_seam ? n : end, from_seam);
      }
    };
    if (!split) {
      pass(0, n, false);
      return;
    }
    RunTasks(threads_, segments, [&](int, int64_t j) {
      pass(j * seg, std::min(n, (j + 1) * seg), false);
    });
    for (int64_t t = 1; t < segments; ++t) {
      const int64_t j = step > 0 ? t : segments - 1 - t;
      pass(j * seg, std::min(n, (j + 1) * seg), true);
    }
    return;
  }
  // Kogge-Stone: `prefix` is the AND of `run` over the last len cells.
  FlatBitset& prefix = scratch_a;
  FlatBitset& tmp = scratch_b;
  tmp.EnsureSize(bits_);
  prefix = run;
  for (int64_t len = 1; len < max_len; len *= 2) {
    tmp.AssignShifted(*this, len * step);
    tmp.And(prefix);
    Or(tmp);
    tmp.AssignShifted(prefix, len * step);
    prefix.And(tmp);
  }
}

void FlatBitset::Dilate26(const int64_t strides[3], FlatBitset& scratch) {
  for (int a = 0; a < 3; ++a) {
    scratch = *this;
    OrShifted(scratch, strides[a]);
    OrShifted(scratch, -strides[a]);
  }
}

int64_t FlatBitset::Count() const {
  const int64_t words = static_cast<int64_t>(words_.size());
  std::vector<int64_t> counts(static_cast<size_t>(WordBlockCount(threads_, words)), 0);
  const uint64_t* w = words_.data();
  ForWordBlocks(threads_, words, [&](int64_t block, int64_t b, int64_t e) {
    int64_t n = 0;
    for (int64_t i = b; i < e; ++i) n += __builtin_popcountll(w[i]);
    counts[static_cast<size_t>(block)] = n;
  });
  int64_t n = 0;
  for (int64_t c : counts) n += c;
  return n;
}

void FlatBitset::ErodeRun(int n, int64_t stride) { ErodeRunFromLength(1, n, stride); }

void FlatBitset::ErodeRunFromLength(int len, int n, int64_t stride) {
  while (2 * len <= n) {
    AndShiftedDown(len * stride);
    len *= 2;
  }
  if (len < n) AndShiftedDown((n - len) * stride);
}

void FlatBitset::ErodeRunFrom(const FlatBitset& src, int n, int64_t stride) {
  const int64_t words = static_cast<int64_t>(words_.size());
  if (n < 2) {
    std::copy(src.words_.begin(), src.words_.end(), words_.begin());
    return;
  }
  // The first doubling step of ErodeRun, this[i] = src[i] & src[i + s], reads src directly.
  CombineShifted(threads_, words_.data(), src.words_.data(), src.words_.data(), words, -stride,
                 [](uint64_t x, uint64_t y) { return x & y; });
  ErodeRunFromLength(2, n, stride);
}

void FlatBitset::DilateRunFrom(const FlatBitset& src, int n, int64_t stride) {
  const int64_t words = static_cast<int64_t>(words_.size());
  if (n < 2) {
    std::copy(src.words_.begin(), src.words_.end(), words_.begin());
    return;
  }
  // The first doubling step of DilateRun, this[i] = src[i] | src[i - s].
  CombineShifted(threads_, words_.data(), src.words_.data(), src.words_.data(), words, stride,
                 [](uint64_t x, uint64_t y) { return x | y; });
  DilateRunFromLength(2, n, stride);
}

void FlatBitset::DilateRun(int n, int64_t stride) { DilateRunFromLength(1, n, stride); }

void FlatBitset::DilateRunFromLength(int len, int n, int64_t stride) {
  while (2 * len <= n) {
    OrShiftedUp(len * stride);
    len *= 2;
  }
  if (len < n) OrShiftedUp((n - len) * stride);
}

}  // namespace membrane

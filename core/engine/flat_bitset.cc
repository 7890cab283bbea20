#include "core/engine/flat_bitset.h"

#include <algorithm>

#include "core/engine/ivdep.h"

namespace membrane {

void FlatBitset::clear_all() { std::fill(words_.begin(), words_.end(), 0); }

bool FlatBitset::any() const {
  return std::any_of(words_.begin(), words_.end(), [](uint64_t w) { return w != 0; });
}

void FlatBitset::And(const FlatBitset& o) {
  for (size_t w = 0; w < words_.size(); ++w) words_[w] &= o.words_[w];
}
void FlatBitset::Or(const FlatBitset& o) {
  for (size_t w = 0; w < words_.size(); ++w) words_[w] |= o.words_[w];
}
void FlatBitset::AndNot(const FlatBitset& o) {
  for (size_t w = 0; w < words_.size(); ++w) words_[w] &= ~o.words_[w];
}

bool FlatBitset::OrChanged(const FlatBitset& o) {
  uint64_t added = 0;
  for (size_t w = 0; w < words_.size(); ++w) {
    added |= o.words_[w] & ~words_[w];
    words_[w] |= o.words_[w];
  }
  return added != 0;
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

void FlatBitset::AndShiftedDown(int64_t k) {
  // Ascending: word w reads words >= w, which are not yet written. The main loop has no
  // bounds checks (this and OrShiftedUp are most of the word operations of a shrink).
  const int64_t n = static_cast<int64_t>(words_.size());
  const int64_t q = k >> 6;
  const int r = static_cast<int>(k & 63);
  uint64_t* w = words_.data();
  const int64_t main_end = std::max<int64_t>(0, n - q - 1);
  if (r == 0) {
    for (int64_t i = 0; i < main_end; ++i) w[i] &= w[i + q];
  } else {
    for (int64_t i = 0; i < main_end; ++i) w[i] &= (w[i + q] >> r) | (w[i + q + 1] << (64 - r));
  }
  for (int64_t i = main_end; i < n; ++i) {
    const uint64_t lo = i + q < n ? w[i + q] : 0;
    const uint64_t hi = (r != 0 && i + q + 1 < n) ? w[i + q + 1] : 0;
    w[i] &= r == 0 ? lo : (lo >> r) | (hi << (64 - r));
  }
}

void FlatBitset::OrShiftedUp(int64_t k) {
  // Descending: word w reads words <= w, which are not yet written.
  const int64_t n = static_cast<int64_t>(words_.size());
  const int64_t q = k >> 6;
  const int r = static_cast<int>(k & 63);
  uint64_t* w = words_.data();
  const int64_t main_begin = std::min<int64_t>(n, q + 1);  // i - q - 1 >= 0 from here
  // Every read is at or below the word written and every earlier write above it, so loading
  // a block of sources before storing its words is exact: ivdep lets GCC vectorize the
  // descending loop, which it would not on its own.
  if (r == 0) {
MEMBRANE_IVDEP
    for (int64_t i = n - 1; i >= main_begin; --i) w[i] |= w[i - q];
  } else {
MEMBRANE_IVDEP
    for (int64_t i = n - 1; i >= main_begin; --i) {
      w[i] |= (w[i - q] << r) | (w[i - q - 1] >> (64 - r));
    }
  }
  for (int64_t i = main_begin - 1; i >= 0; --i) {
    const int64_t src = i - q;
    const uint64_t hi = src >= 0 ? w[src] : 0;
    const uint64_t lo = (r != 0 && src - 1 >= 0) ? w[src - 1] : 0;
    w[i] |= r == 0 ? hi : (hi << r) | (lo >> (64 - r));
  }
}

namespace {

// Applies dst[w] = op(base[w], the 64 bits of src starting at bit w * 64 - k) to every word,
// with the word offset and bit shift computed once (bits outside src read as 0). `base` is
// dst itself for the in-place operations.
template <typename Op>
void CombineShifted(uint64_t* dst, const uint64_t* base, const uint64_t* src, int64_t words,
                    int64_t k, Op op) {
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
  const int64_t first = std::clamp<int64_t>(-q, 0, words);
  const int64_t last = std::clamp<int64_t>(words - q - 1, first, words);
  int64_t w = 0;
  for (; w < first; ++w) dst[w] = op(base[w], get(w));
  if (r == 0) {
    for (; w < last; ++w) dst[w] = op(base[w], src[w + q]);
  } else {
    for (; w < last; ++w) dst[w] = op(base[w], (src[w + q] >> r) | (src[w + q + 1] << (64 - r)));
  }
  for (; w < words; ++w) dst[w] = op(base[w], get(w));
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
  CombineShifted(words_.data(), words_.data(), other.words_.data(),
                 static_cast<int64_t>(words_.size()), k,
                 [](uint64_t, uint64_t b) { return b; });
}

void FlatBitset::OrShifted(const FlatBitset& other, int64_t k) {
  CombineShifted(words_.data(), words_.data(), other.words_.data(),
                 static_cast<int64_t>(words_.size()), k,
                 [](uint64_t a, uint64_t b) { return a | b; });
}

void FlatBitset::AndShifted(const FlatBitset& other, int64_t k) {
  CombineShifted(words_.data(), words_.data(), other.words_.data(),
                 static_cast<int64_t>(words_.size()), k,
                 [](uint64_t a, uint64_t b) { return a & b; });
}

void FlatBitset::AssignAndShifted(const FlatBitset& a, const FlatBitset& b, int64_t k) {
  CombineShifted(words_.data(), a.words_.data(), b.words_.data(),
                 static_cast<int64_t>(words_.size()), k,
                 [](uint64_t x, uint64_t y) { return x & y; });
}

void FlatBitset::AssignOr(const FlatBitset& a, const FlatBitset& b) {
  for (size_t w = 0; w < words_.size(); ++w) words_[w] = a.words_[w] | b.words_[w];
}

void FlatBitset::AssignOrAnd(const FlatBitset& a, const FlatBitset& b, const FlatBitset& c) {
  for (size_t w = 0; w < words_.size(); ++w) {
    words_[w] = (a.words_[w] | b.words_[w]) & c.words_[w];
  }
}

void FlatBitset::SpreadAlong(const FlatBitset& run, int64_t step, int64_t max_len,
                             FlatBitset& scratch_a, FlatBitset& scratch_b) {
  const int64_t n = static_cast<int64_t>(words_.size());
  const int64_t mag = step < 0 ? -step : step;
  if (mag >= 64) {
    // Every source bit of word w lies in an earlier word in the order of the step, which is
    // already final: one pass.
    const int64_t q = mag / 64;
    const int r = static_cast<int>(mag % 64);
    const uint64_t* run_w = run.words_.data();
    uint64_t* w = words_.data();
    if (step > 0) {
      for (int64_t k = q; k < n; ++k) {
        // Bits k*64 - mag ... : words k - q - 1 (high part) and k - q.
        const uint64_t hi = w[k - q];
        const uint64_t lo = k - q - 1 >= 0 ? w[k - q - 1] : 0;
        const uint64_t src = r == 0 ? hi : (hi << r) | (lo >> (64 - r));
        w[k] |= run_w[k] & src;
      }
    } else {
      for (int64_t k = n - 1 - q; k >= 0; --k) {
        const uint64_t lo = w[k + q];
        const uint64_t hi = k + q + 1 < n ? w[k + q + 1] : 0;
        const uint64_t src = r == 0 ? lo : (lo >> r) | (hi << (64 - r));
        w[k] |= run_w[k] & src;
      }
    }
    return;
  }
  if (mag == 1) {
    // Along x: one pass, the top (resp. bottom) result bit of a word seeding the next word.
    const uint64_t* run_w = run.words_.data();
    uint64_t* w = words_.data();
    uint64_t carry = 0;
    if (step > 0) {
      for (int64_t k = 0; k < n; ++k) {
        const uint64_t r = run_w[k];
        w[k] = FillUp(r, w[k] | (carry & r & 1));
        carry = w[k] >> 63;
      }
    } else {
      // Downwards is upwards in bit-reversed words, taken from the highest word down.
      for (int64_t k = n - 1; k >= 0; --k) {
        const uint64_t r = ReverseBits(run_w[k]);
        const uint64_t filled = FillUp(r, ReverseBits(w[k]) | (carry & r & 1));
        w[k] = ReverseBits(filled);
        carry = filled >> 63;
      }
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
  int64_t n = 0;
  for (uint64_t w : words_) n += __builtin_popcountll(w);
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
  CombineShifted(words_.data(), src.words_.data(), src.words_.data(), words, -stride,
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
  CombineShifted(words_.data(), src.words_.data(), src.words_.data(), words, stride,
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

#include "core/engine/flat_bitset.h"

#include <algorithm>

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
  // Ascending: word w reads words >= w, which are not yet written.
  const int64_t n = static_cast<int64_t>(words_.size());
  const int64_t q = k >> 6;
  const int r = static_cast<int>(k & 63);
  for (int64_t w = 0; w < n; ++w) {
    const uint64_t lo = w + q < n ? words_[static_cast<size_t>(w + q)] : 0;
    const uint64_t hi = (r != 0 && w + q + 1 < n) ? words_[static_cast<size_t>(w + q + 1)] : 0;
    words_[static_cast<size_t>(w)] &= r == 0 ? lo : (lo >> r) | (hi << (64 - r));
  }
}

void FlatBitset::OrShiftedUp(int64_t k) {
  // Descending: word w reads words <= w, which are not yet written.
  const int64_t n = static_cast<int64_t>(words_.size());
  const int64_t q = k >> 6;
  const int r = static_cast<int>(k & 63);
  for (int64_t w = n - 1; w >= 0; --w) {
    const int64_t src = w - q;
    const uint64_t hi = src >= 0 ? words_[static_cast<size_t>(src)] : 0;
    const uint64_t lo = (r != 0 && src - 1 >= 0) ? words_[static_cast<size_t>(src - 1)] : 0;
    words_[static_cast<size_t>(w)] |= r == 0 ? hi : (hi << r) | (lo >> (64 - r));
  }
}

void FlatBitset::AssignShifted(const FlatBitset& other, int64_t k) {
  for (size_t w = 0; w < words_.size(); ++w)
    words_[w] = other.WordAt(static_cast<int64_t>(w) * 64 - k);
}

void FlatBitset::ErodeRun(int n, int64_t stride) {
  int len = 1;
  while (2 * len <= n) {
    AndShiftedDown(len * stride);
    len *= 2;
  }
  if (len < n) AndShiftedDown((n - len) * stride);
}

void FlatBitset::DilateRun(int n, int64_t stride) {
  int len = 1;
  while (2 * len <= n) {
    OrShiftedUp(len * stride);
    len *= 2;
  }
  if (len < n) OrShiftedUp((n - len) * stride);
}

}  // namespace membrane

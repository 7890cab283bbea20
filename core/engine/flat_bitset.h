// A bitset over the flat voxel index, with the run operations of fast-shrink.md section 1:
// a move by one voxel along an axis is a shift of the whole bitset by that axis' stride, so
// 2-D and 3-D erosions and dilations become word operations whatever the axis.
//
// A bitset's word passes run on threads() threads (set_threads), split in fixed blocks of words
// (word_blocks.h) or, for the passes that carry bits from word to word, in fixed segments
// joined in order: every operation gives the same bits for any thread count.
#ifndef MEMBRANE_CORE_ENGINE_FLAT_BITSET_H_
#define MEMBRANE_CORE_ENGINE_FLAT_BITSET_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/engine/arena_allocator.h"

namespace membrane {

class FlatBitset {
 public:
  FlatBitset() = default;
  explicit FlatBitset(int64_t bits) : bits_(bits), words_(static_cast<size_t>((bits + 63) / 64), 0) {}
  // The same, with the words taken from `arena` while it has room (it must outlive this).
  FlatBitset(int64_t bits, PlaneArena* arena)
      : bits_(bits),
        words_(static_cast<size_t>((bits + 63) / 64), 0, UnfilledAllocator<uint64_t>(arena)) {}
  // Tag of the constructor that leaves the words unset.
  struct Unset {};
  // The same with the words unset: the caller writes every word before reading any
  // (clear_all() on threads(): a large plane's first writes are its page faults).
  FlatBitset(int64_t bits, PlaneArena* arena, Unset)
      : bits_(bits),
        words_(static_cast<size_t>((bits + 63) / 64), UnfilledAllocator<uint64_t>(arena)) {}

  FlatBitset(const FlatBitset& other)
      : bits_(other.bits_), threads_(other.threads_), words_(other.words_) {}
  FlatBitset(FlatBitset&&) = default;
  FlatBitset& operator=(FlatBitset&&) = default;
  // A copy of `other`'s bits (threads() is this bitset's own when the sizes match, other's
  // otherwise); the words are copied on threads() threads when the sizes match.
  FlatBitset& operator=(const FlatBitset& other);

  int64_t bits() const { return bits_; }
  // Makes this a zeroed bitset of `bits` bits unless it already has that size; threads() stays.
  void EnsureSize(int64_t bits) {
    if (bits_ == bits) return;
    const int threads = threads_;
    *this = FlatBitset(bits);
    threads_ = threads;
  }
  // Threads the word passes that write this bitset run on (>= 1; default 1).
  int threads() const { return threads_; }
  void set_threads(int threads) { threads_ = threads < 1 ? 1 : threads; }
  // Makes the passes that save a halo (below) save it in `store` instead of a buffer of
  // their own, so that bitsets whose passes never run at the same time hold one between them
  // (a work plane's halo is up to a sixteenth of its bytes). `store` must outlive the bitset;
  // null gives the bitset its own buffer again. A copy of the bitset has its own.
  void set_halo_store(std::vector<uint64_t>* store) { halo_store_ = store; }
  size_t word_count() const { return words_.size(); }
  uint64_t* words() { return words_.data(); }
  const uint64_t* words() const { return words_.data(); }

  bool test(int64_t i) const { return (words_[static_cast<size_t>(i >> 6)] >> (i & 63)) & 1; }
  void set(int64_t i) { words_[static_cast<size_t>(i >> 6)] |= 1ull << (i & 63); }
  void reset(int64_t i) { words_[static_cast<size_t>(i >> 6)] &= ~(1ull << (i & 63)); }
  void clear_all();
  bool any() const;

  // this[i] &= other[i] (resp. |=, = a & b); sizes must match.
  void And(const FlatBitset& other);
  void Or(const FlatBitset& other);
  void AndNot(const FlatBitset& other);
  // this[i] |= other[i]; true when some bit was not set before (one pass for both).
  bool OrChanged(const FlatBitset& other);

  // this[i] &= this[i + k] for k >= 0 (bits past the end read as 0).
  void AndShiftedDown(int64_t k);
  // this[i] |= this[i - k] for k >= 0 (bits before the start read as 0).
  void OrShiftedUp(int64_t k);
  // this[i] = other[i - k] (k may be negative: this[i] = other[i + |k|]); likewise |= and &=.
  void AssignShifted(const FlatBitset& other, int64_t k);
  void OrShifted(const FlatBitset& other, int64_t k);
  void AndShifted(const FlatBitset& other, int64_t k);
  // this[i] = a[i] & b[i - k] in one pass (a copy of `a` and AndShifted would be two); a, b
  // and this must have the same size; this may be neither a nor b.
  void AssignAndShifted(const FlatBitset& a, const FlatBitset& b, int64_t k);
  // this[i] = a[i] | b[i], one pass; sizes must match.
  void AssignOr(const FlatBitset& a, const FlatBitset& b);
  // this[i] = (a[i] | b[i]) & c[i], one pass; sizes must match.
  void AssignOrAnd(const FlatBitset& a, const FlatBitset& b, const FlatBitset& c);
  // Seeded runs: this[i] |= run[i] & this[i - step] applied in the order of the step, so a
  // set bit spreads along `step` (positive or negative) while `run` stays set. `this` must be a
  // subset of `run`. One pass when |step| >= 64 or |step| == 1 (carries of an addition run
  // along x); doubling (log2 of `max_len` passes) otherwise, using `scratch_a` and `scratch_b`
  // (resized when needed; their contents are overwritten).
  void SpreadAlong(const FlatBitset& run, int64_t step, int64_t max_len, FlatBitset& scratch_a,
                   FlatBitset& scratch_b);
  // Dilation by the 3x3x3 box: this[i] |= this[j] for every j 26-adjacent to i, given the
  // three axis strides. Needs a border of zeros one voxel wide to avoid wrapping. `scratch`
  // (same size) is overwritten: callers keep one so that no plane is allocated per call.
  void Dilate26(const int64_t strides[3], FlatBitset& scratch);
  // Number of set bits.
  int64_t Count() const;
  // Calls f(i) for every set bit i, in increasing order.
  template <typename F>
  void ForEach(F f) const {
    ForEachInWords(0, static_cast<int64_t>(words_.size()), [&](int64_t i) {
      f(i);
      return true;
    });
  }
  // Calls visit(i) for the set bits i of words [begin, end), in increasing order, until visit
  // returns false; returns false when it stopped so.
  template <typename Visit>
  bool ForEachInWords(int64_t begin, int64_t end, Visit visit) const {
    for (int64_t w = begin; w < end; ++w) {
      for (uint64_t bits = words_[static_cast<size_t>(w)]; bits != 0; bits &= bits - 1) {
        if (!visit(w * 64 + __builtin_ctzll(bits))) return false;
      }
    }
    return true;
  }

  // Erosion by a run of n along stride s, anchored at the lowest cell:
  // this[i] = AND_{j<n} this[i + j s]. ceil(log2 n) + 1 passes.
  void ErodeRun(int n, int64_t stride);
  // Dilation by a run of n along stride s: this[i] = OR_{j<n} this[i - j s].
  void DilateRun(int n, int64_t stride);
  // this = src eroded (resp. dilated) by a run of n >= 1 along stride s, as a copy then
  // ErodeRun (DilateRun) would give, with the copy folded into the first pass. `src` must
  // have this bitset's size and must not be this bitset.
  void ErodeRunFrom(const FlatBitset& src, int n, int64_t stride);
  void DilateRunFrom(const FlatBitset& src, int n, int64_t stride);
  // The same four runs (same bits) in a number of passes that does not grow with n: one pass
  // along x (stride 1) for n >= 64, three along a stride of 129 or more for n >= 17 (blocks of
  // n along the stride, van Herk / Gil-Werman), the doubling passes otherwise.
  // `scratch` must have this bitset's size and be neither this bitset nor `src`; its
  // contents are overwritten. Defined in flat_bitset_long_runs.cc.
  void ErodeRun(int n, int64_t stride, FlatBitset& scratch);
  void DilateRun(int n, int64_t stride, FlatBitset& scratch);
  void ErodeRunFrom(const FlatBitset& src, int n, int64_t stride, FlatBitset& scratch);
  void DilateRunFrom(const FlatBitset& src, int n, int64_t stride, FlatBitset& scratch);

 private:
  // ErodeRun (DilateRun) for a bitset already eroded (dilated) by a run of `len` <= n: the
  // doubling passes from there on.
  void ErodeRunFromLength(int len, int n, int64_t stride);
  void DilateRunFromLength(int len, int n, int64_t stride);
  // The buffer the in-place shifted passes save their halo in.
  std::vector<uint64_t>& halo() { return halo_store_ != nullptr ? *halo_store_ : halo_; }
  // The 64 bits starting at bit position `pos` (may be negative or past the end: zeros).
  uint64_t WordAt(int64_t pos) const;

  int64_t bits_ = 0;
  int threads_ = 1;
  std::vector<uint64_t, UnfilledAllocator<uint64_t>> words_;
  // The words the in-place shifted passes on threads save before they write (at most a
  // sixteenth of the bitset; empty on one thread), unless halo_store_ holds them.
  std::vector<uint64_t> halo_;
  std::vector<uint64_t>* halo_store_ = nullptr;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_FLAT_BITSET_H_

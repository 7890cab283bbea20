// The queue of edge collapses of the decimation (mesh_decimation.h): costs sorted into buckets
// of their float bits instead of a binary heap. A heap of the 20M edges of a 15M-face mesh
// spans 400 MB, and each pop follows ~25 levels of it at random: memory latency, per pop,
// for ten pops per collapse. A bucket is a vector appended and taken from its end.
#ifndef MEMBRANE_CORE_MESH_COLLAPSE_QUEUE_H_
#define MEMBRANE_CORE_MESH_COLLAPSE_QUEUE_H_

#include <algorithm>
#include <bit>
#include <cstdint>
#include <vector>

namespace membrane {

// An edge (a, b) and the stamps its vertices had when its cost was computed: the entry is
// stale once either stamp has moved on.
struct CollapseCandidate {
  float cost;  // >= 0
  int32_t a, b;
  uint32_t stamp_a, stamp_b;
};

class CollapseQueue {
 public:
  bool empty() const { return size_ == 0; }
  int64_t size() const { return size_; }

  void Push(const CollapseCandidate& c) {
    if (buckets_.empty()) {
      buckets_.resize(kBuckets);
      nonempty_.assign(kBuckets / 64, 0);
    }
    const size_t k = Bucket(c.cost);
    if (buckets_[k].empty()) nonempty_[k / 64] |= uint64_t{1} << (k % 64);
    buckets_[k].push_back(c);
    if (k < lowest_) lowest_ = k;
    ++size_;
  }

  // One entry of least cost up to a relative 2^-9 (costs whose float bits agree but for the
  // last 14 share a bucket; of those the last pushed comes first). Not empty().
  CollapseCandidate Pop() {
    while (buckets_[lowest_].empty()) {
      // The next non-empty bucket: the first set bit at or after lowest_.
      size_t word = lowest_ / 64;
      uint64_t bits = nonempty_[word] & (~uint64_t{0} << (lowest_ % 64));
      while (bits == 0) bits = nonempty_[++word];
      lowest_ = word * 64 + static_cast<size_t>(std::countr_zero(bits));
    }
    std::vector<CollapseCandidate>& bucket = buckets_[lowest_];
    const CollapseCandidate c = bucket.back();
    bucket.pop_back();
    if (bucket.empty()) {
      nonempty_[lowest_ / 64] &= ~(uint64_t{1} << (lowest_ % 64));
      if (bucket.capacity() > 4096) std::vector<CollapseCandidate>().swap(bucket);
    }
    --size_;
    return c;
  }

  void Clear() {
    buckets_.clear();
    nonempty_.clear();
    lowest_ = kBuckets;
    size_ = 0;
  }

 private:
  static constexpr int kDroppedBits = 14;
  // Non-negative floats, +infinity included, have bit patterns below 2^31, in their order.
  static constexpr size_t kBuckets = size_t{1} << (31 - kDroppedBits);
  static size_t Bucket(float cost) {
    const uint32_t bits = std::bit_cast<uint32_t>(cost > 0 ? cost : 0.0f);
    return std::min<size_t>(bits >> kDroppedBits, kBuckets - 1);
  }

  std::vector<std::vector<CollapseCandidate>> buckets_;
  std::vector<uint64_t> nonempty_;  // one bit per bucket
  size_t lowest_ = kBuckets;        // no bucket below it holds an entry
  int64_t size_ = 0;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_COLLAPSE_QUEUE_H_

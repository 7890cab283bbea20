#include "core/mesh/border_flood.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstdint>
#include <vector>

#include "core/base/parallel_tasks.h"

namespace membrane {
namespace {

constexpr uint64_t kAll = ~uint64_t{0};

// Planes of a slab, at least: a thinner slab sends most of its runs across its faces.
constexpr int kMinSlabPlanes = 8;

// The reached bits. On slabs, two slabs' planes may share the word at their meeting: each
// slab sets only its own voxels' bits and reads only its own voxels' (or, between rounds, its
// neighbours'), so word accesses are relaxed atomics and setting bits is an atomic OR.
template <bool kShared>
class Marks {
 public:
  explicit Marks(FlatBitset& bits) : words_(bits.words()) {}
  uint64_t Load(int64_t w) const {
    if constexpr (kShared) return std::atomic_ref<uint64_t>(words_[w]).load(std::memory_order_relaxed);
    else return words_[w];
  }
  void Or(int64_t w, uint64_t v) const {
    if constexpr (kShared) std::atomic_ref<uint64_t>(words_[w]).fetch_or(v, std::memory_order_relaxed);
    else words_[w] |= v;
  }
  void Fill(int64_t w) const {
    if constexpr (kShared) std::atomic_ref<uint64_t>(words_[w]).store(kAll, std::memory_order_relaxed);
    else words_[w] = kAll;
  }
  void Set(int64_t i) const { Or(i >> 6, uint64_t{1} << (i & 63)); }
  bool Test(int64_t i) const { return (Load(i >> 6) >> (i & 63)) & 1; }

 private:
  uint64_t* words_;
};

// Free voxels are open and not yet reached.
template <bool kShared>
uint64_t Free(const FlatBitset& open, const Marks<kShared>& reached, int64_t word) {
  return open.words()[word] & ~reached.Load(word);
}

// The first index >= from whose voxel is not free. One exists below the array's end when a
// voxel at or after `from` is not free (the caller's last voxel is on the border).
template <bool kShared>
int64_t FirstNotFree(const FlatBitset& open, const Marks<kShared>& reached, int64_t from) {
  int64_t word = from >> 6;
  uint64_t stop = ~Free(open, reached, word) & (kAll << (from & 63));
  while (stop == 0) stop = ~Free(open, reached, ++word);
  return word * 64 + std::countr_zero(stop);
}

// The last index <= from whose voxel is not free (likewise one exists from voxel 0 on).
template <bool kShared>
int64_t LastNotFree(const FlatBitset& open, const Marks<kShared>& reached, int64_t from) {
  int64_t word = from >> 6;
  uint64_t stop = ~Free(open, reached, word) & (kAll >> (63 - (from & 63)));
  while (stop == 0) stop = ~Free(open, reached, --word);
  return word * 64 + 63 - std::countl_zero(stop);
}

// Sets bits lo..hi (of one row: the words strictly inside are the row's own).
template <bool kShared>
void SetRange(const Marks<kShared>& reached, int64_t lo, int64_t hi) {
  const int64_t first = lo >> 6, last = hi >> 6;
  const uint64_t head = kAll << (lo & 63), tail = kAll >> (63 - (hi & 63));
  if (first == last) {
    reached.Or(first, head & tail);
    return;
  }
  reached.Or(first, head);
  for (int64_t w = first + 1; w < last; ++w) reached.Fill(w);
  reached.Or(last, tail);
}

// For the voxels from..to (one row segment): each run of free voxels gets its first voxel
// marked reached and pushed on `stack`, a word of 64 voxels at a time.
template <bool kShared>
void SeedRuns(const FlatBitset& open, const Marks<kShared>& reached, int64_t from, int64_t to,
              std::vector<int64_t>& stack) {
  const int64_t first = from >> 6, last = to >> 6;
  uint64_t carry = 0;  // 1 when the voxel before this word is free and in the segment
  for (int64_t w = first; w <= last; ++w) {
    uint64_t in = kAll;
    if (w == first) in &= kAll << (from & 63);
    if (w == last) in &= kAll >> (63 - (to & 63));
    const uint64_t free = Free(open, reached, w) & in;
    uint64_t starts = free & ~((free << 1) | carry);
    carry = free >> 63;
    if (starts == 0) continue;
    reached.Or(w, starts);
    for (; starts != 0; starts &= starts - 1) stack.push_back(w * 64 + std::countr_zero(starts));
  }
}

// The grid's strides and the planes [z0, z1) a flood may enter.
struct FloodBox {
  int n[3];
  int64_t step[3];
  int z0, z1;
};

// Marks the open border voxels of planes [z0, z1) and pushes the open voxels one layer in that
// touch one. The border voxels are marked but never expanded (their neighbours may not exist).
// Every voxel one layer in is interior, and every voxel the flood reaches from them is interior
// or already marked, so no run crosses the end of a row.
template <bool kShared>
void SeedFromBorder(const FloodBox& box, const FlatBitset& open, const Marks<kShared>& reached,
                    std::vector<int64_t>& stack) {
  const int* n = box.n;
  for (int z = box.z0; z < box.z1; ++z)
    for (int y = 0; y < n[1]; ++y)
      for (int x = 0; x < n[0]; ++x) {
        const int c[3] = {x, y, z};
        int on_border = 0, on_layer1 = 0;
        for (int a = 0; a < 3; ++a) {
          on_border |= c[a] == 0 || c[a] == n[a] - 1;
          on_layer1 |= c[a] == 1 || c[a] == n[a] - 2;
        }
        if (!on_border && !on_layer1) {
          x = n[0] - 3;  // jump to the far layer-1 voxel of this row
          continue;
        }
        const int64_t i = x + y * box.step[1] + z * box.step[2];
        if (on_border) {
          if (open.test(i)) reached.Set(i);
          continue;
        }
        if (!open.test(i)) continue;
        for (int a = 0; a < 3; ++a)
          if ((c[a] == 1 && open.test(i - box.step[a])) ||
              (c[a] == n[a] - 2 && open.test(i + box.step[a]))) {
            reached.Set(i);
            stack.push_back(i);
            break;
          }
      }
}

// Scanline flood: each popped seed (marked) is extended into its whole run along x, and each
// run seeds the rows next to it inside planes [z0, z1), 64 voxels a word.
template <bool kShared>
void Flood(const FloodBox& box, const FlatBitset& open, const Marks<kShared>& reached,
           std::vector<int64_t>& stack) {
  while (!stack.empty()) {
    const int64_t seed = stack.back();
    stack.pop_back();
    const int64_t lo = LastNotFree(open, reached, seed - 1) + 1;
    const int64_t hi = FirstNotFree(open, reached, seed + 1) - 1;
    SetRange(reached, lo, hi);
    const int z = static_cast<int>(lo / box.step[2]);
    for (int a = 1; a < 3; ++a)
      for (int dir : {-1, 1}) {
        if (a == 2 && (z + dir < box.z0 || z + dir >= box.z1)) continue;
        const int64_t offset = dir * box.step[a];
        SeedRuns(open, reached, lo + offset, hi + offset, stack);
      }
  }
}

// The free voxels of plane `z` whose neighbour in plane z + dir is reached, as the first voxel
// of each run of them along the flat index (a run of free voxels may get several).
void FaceSeeds(const FloodBox& box, const FlatBitset& open, const Marks<true>& reached, int z,
               int dir, std::vector<int64_t>& seeds) {
  const int64_t begin = z * box.step[2], end = begin + box.step[2];  // the plane's voxels
  const int64_t shift = dir * box.step[2];
  uint64_t carry = 0;
  for (int64_t w = begin >> 6; w <= (end - 1) >> 6; ++w) {
    uint64_t in = kAll;
    if (w == begin >> 6) in &= kAll << (begin & 63);
    if (w == (end - 1) >> 6) in &= kAll >> (63 - ((end - 1) & 63));
    // The reached bits of voxels w * 64 + shift .. + 63 (all in the array where `in` is set).
    const int64_t from = w * 64 + shift;
    const int64_t q = from >> 6;
    const int r = static_cast<int>(from & 63);
    uint64_t next = 0;
    if (from >= 0) next = reached.Load(q) >> r;
    if (r != 0 && (q + 1) * 64 < open.bits()) next |= reached.Load(q + 1) << (64 - r);
    const uint64_t cand = Free(open, reached, w) & next & in;
    uint64_t starts = cand & ~((cand << 1) | carry);
    carry = cand >> 63;
    for (; starts != 0; starts &= starts - 1) seeds.push_back(w * 64 + std::countr_zero(starts));
  }
}

FlatBitset SerialFlood(const FloodBox& box, const FlatBitset& open) {
  FlatBitset reached(open.bits());
  const Marks<false> marks(reached);
  std::vector<int64_t> stack;
  SeedFromBorder(box, open, marks, stack);
  Flood(box, open, marks, stack);
  return reached;
}

// Slabs of z planes on the threads, in rounds: each slab floods its own planes; between
// rounds, each slab seeds the free voxels of its two face planes whose neighbour across the
// face was reached; the rounds end when no slab has a seed. The reached set is the flood's
// closure, the same whichever slab reaches a voxel first.
FlatBitset SlabFlood(const FloodBox& whole, const FlatBitset& open, int threads, int slabs) {
  FlatBitset reached(open.bits(), nullptr, FlatBitset::Unset{});
  reached.set_threads(threads);
  reached.clear_all();  // on the threads: the first writes of a large bitset are page faults
  const Marks<true> marks(reached);
  const int nz = whole.n[2];
  slabs = std::clamp(slabs, 1, std::max(nz, 1));
  std::vector<FloodBox> boxes(slabs, whole);
  for (int k = 0; k < slabs; ++k) {
    boxes[k].z0 = static_cast<int>(int64_t{nz} * k / slabs);
    boxes[k].z1 = static_cast<int>(int64_t{nz} * (k + 1) / slabs);
  }
  std::vector<std::vector<int64_t>> stacks(slabs);
  RunTasks(threads, slabs, [&](int, int64_t k) {
    SeedFromBorder(boxes[k], open, marks, stacks[k]);
    Flood(boxes[k], open, marks, stacks[k]);
  });
  for (;;) {
    std::atomic<bool> seeded{false};
    RunTasks(threads, slabs, [&](int, int64_t k) {
      const FloodBox& box = boxes[k];
      if (box.z0 > 0) FaceSeeds(box, open, marks, box.z0, -1, stacks[k]);
      if (box.z1 < nz) FaceSeeds(box, open, marks, box.z1 - 1, 1, stacks[k]);
      if (!stacks[k].empty()) seeded.store(true, std::memory_order_relaxed);
    });
    if (!seeded.load()) break;
    RunTasks(threads, slabs, [&](int, int64_t k) {
      std::vector<int64_t>& stack = stacks[k];
      size_t kept = 0;
      for (int64_t i : stack)
        if (!marks.Test(i)) {
          marks.Set(i);
          stack[kept++] = i;
        }
      stack.resize(kept);
      Flood(boxes[k], open, marks, stack);
    });
  }
  return reached;
}

FloodBox WholeArray(const std::array<int, 3>& dims) {
  FloodBox box;
  for (int a = 0; a < 3; ++a) box.n[a] = dims[a];
  box.step[0] = 1;
  box.step[1] = dims[0];
  box.step[2] = int64_t{dims[0]} * dims[1];
  box.z0 = 0;
  box.z1 = dims[2];
  return box;
}

}  // namespace

FlatBitset FloodFromBorder(const std::array<int, 3>& dims, const FlatBitset& open, int threads) {
  if (threads <= 1 || open.bits() < kMinSplitGridVoxels || dims[2] < 2 * kMinSlabPlanes)
    return SerialFlood(WholeArray(dims), open);
  // Many slabs a thread: the open runs are not spread evenly over the planes, and a round
  // waits for its last slab (at 4 a thread, one thread idled the last sixth of the 4M
  // torus's flood).
  const int slabs = std::min(dims[2] / kMinSlabPlanes, 16 * threads);
  return SlabFlood(WholeArray(dims), open, threads, slabs);
}

FlatBitset FloodFromBorderOnSlabs(const std::array<int, 3>& dims, const FlatBitset& open,
                                  int threads, int slabs) {
  return SlabFlood(WholeArray(dims), open, threads, slabs);
}

}  // namespace membrane

#include "core/mesh/border_flood.h"

#include <bit>
#include <cstdint>
#include <vector>

namespace membrane {
namespace {

constexpr uint64_t kAll = ~uint64_t{0};

// Free voxels are open and not yet reached.
uint64_t Free(const FlatBitset& open, const FlatBitset& reached, int64_t word) {
  return open.words()[word] & ~reached.words()[word];
}

// The first index >= from whose voxel is not free. One exists below the array's end when a
// voxel at or after `from` is not free (the caller's last voxel is on the border).
int64_t FirstNotFree(const FlatBitset& open, const FlatBitset& reached, int64_t from) {
  int64_t word = from >> 6;
  uint64_t stop = ~Free(open, reached, word) & (kAll << (from & 63));
  while (stop == 0) stop = ~Free(open, reached, ++word);
  return word * 64 + std::countr_zero(stop);
}

// The last index <= from whose voxel is not free (likewise one exists from voxel 0 on).
int64_t LastNotFree(const FlatBitset& open, const FlatBitset& reached, int64_t from) {
  int64_t word = from >> 6;
  uint64_t stop = ~Free(open, reached, word) & (kAll >> (63 - (from & 63)));
  while (stop == 0) stop = ~Free(open, reached, --word);
  return word * 64 + 63 - std::countl_zero(stop);
}

// Sets bits lo..hi.
void SetRange(FlatBitset& set, int64_t lo, int64_t hi) {
  uint64_t* const bits = set.words();
  const int64_t first = lo >> 6, last = hi >> 6;
  const uint64_t head = kAll << (lo & 63), tail = kAll >> (63 - (hi & 63));
  if (first == last) {
    bits[first] |= head & tail;
    return;
  }
  bits[first] |= head;
  for (int64_t w = first + 1; w < last; ++w) bits[w] = kAll;
  bits[last] |= tail;
}

// For the voxels from..to (one row segment): each run of free voxels gets its first voxel
// marked reached and pushed on `stack`, a word of 64 voxels at a time.
void SeedRuns(const FlatBitset& open, FlatBitset& reached, int64_t from, int64_t to,
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
    reached.words()[w] |= starts;
    for (; starts != 0; starts &= starts - 1) stack.push_back(w * 64 + std::countr_zero(starts));
  }
}

}  // namespace

FlatBitset FloodFromBorder(const std::array<int, 3>& dims, const FlatBitset& open) {
  const int n[3] = {dims[0], dims[1], dims[2]};
  const int64_t step[3] = {1, n[0], int64_t{n[0]} * n[1]};
  FlatBitset reached(open.bits());
  std::vector<int64_t> stack;
  // The border voxels are marked but never expanded (their neighbours may not exist). Every
  // voxel one layer in is interior; those touching an open border voxel seed the flood, and
  // every voxel the flood reaches from them is interior or already marked, so no run crosses
  // the end of a row.
  for (int z = 0; z < n[2]; ++z)
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
        const int64_t i = x + y * step[1] + z * step[2];
        if (on_border) {
          if (open.test(i)) reached.set(i);
          continue;
        }
        if (!open.test(i)) continue;
        for (int a = 0; a < 3; ++a)
          if ((c[a] == 1 && open.test(i - step[a])) ||
              (c[a] == n[a] - 2 && open.test(i + step[a]))) {
            reached.set(i);
            stack.push_back(i);
            break;
          }
      }
  // Scanline flood: each popped seed is extended into its whole run along x, and each run
  // seeds the rows next to it, 64 voxels a word.
  while (!stack.empty()) {
    const int64_t seed = stack.back();
    stack.pop_back();
    const int64_t lo = LastNotFree(open, reached, seed - 1) + 1;
    const int64_t hi = FirstNotFree(open, reached, seed + 1) - 1;
    SetRange(reached, lo, hi);
    for (int a = 1; a < 3; ++a)
      for (int64_t offset : {-step[a], step[a]}) SeedRuns(open, reached, lo + offset, hi + offset, stack);
  }
  return reached;
}

}  // namespace membrane

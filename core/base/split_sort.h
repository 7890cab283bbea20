// A sort of unique items split over two threads, for the large index sorts of a run (the
// surface's Morton order, the shrink's points by voxel).
#ifndef MEMBRANE_CORE_BASE_SPLIT_SORT_H_
#define MEMBRANE_CORE_BASE_SPLIT_SORT_H_

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/base/parallel_tasks.h"

namespace membrane {

// Below this many items a sort is not split: starting a thread costs more than it saves.
inline constexpr size_t kMinSplitItems = size_t{1} << 16;

// Sets items[i] = make(i) for every i of `items` (a std::vector of any allocator, sized by the
// caller) and sorts them ascending. With threads > 1 and at least kMinSplitItems items, each
// half is made and sorted on a thread of its own and the halves are merged, 4 parts a thread
// side by side (a second buffer of the items' type and size while merging). The items must be
// unique (no two compare equal): the result is then the one std::sort gives, for any thread
// count. `make` is called from several threads at once.
template <typename Vector, typename Make>
void MakeAndSortUnique(Vector& items, int threads, Make make) {
  const size_t n = items.size();
  const int64_t halves = threads > 1 && n >= kMinSplitItems ? 2 : 1;
  const size_t middle = halves == 2 ? n / 2 : n;
  RunTasks(threads, halves, [&](int, int64_t half) {
    const size_t begin = half == 0 ? 0 : middle, end = half == 0 ? middle : n;
    for (size_t i = begin; i < end; ++i) items[i] = make(i);
    std::sort(items.begin() + static_cast<std::ptrdiff_t>(begin),
              items.begin() + static_cast<std::ptrdiff_t>(end));
  });
  if (halves == 2) {
    // Part p writes the merge's items [n p / parts, n (p + 1) / parts): it takes the first i
    // of them from the first half, where i is the one count for which every item taken comes
    // before every item left (merge path; unique items, so exactly one i).
    const auto a = items.begin();
    const auto b = items.begin() + static_cast<std::ptrdiff_t>(middle);
    const size_t nb = n - middle;
    auto from_first = [&](size_t k) {
      size_t lo = k > nb ? k - nb : 0, hi = std::min(k, middle);
      while (lo < hi) {
        const size_t i = lo + (hi - lo) / 2;
        if (a[static_cast<std::ptrdiff_t>(i)] < b[static_cast<std::ptrdiff_t>(k - i - 1)]) {
          lo = i + 1;
        } else {
          hi = i;
        }
      }
      return lo;
    };
    Vector merged(n);
    const int64_t parts = 4 * int64_t{threads};
    RunTasks(threads, parts, [&](int, int64_t p) {
      const size_t k0 = n * static_cast<size_t>(p) / static_cast<size_t>(parts);
      const size_t k1 = n * static_cast<size_t>(p + 1) / static_cast<size_t>(parts);
      const size_t i0 = from_first(k0), i1 = from_first(k1);
      std::merge(a + static_cast<std::ptrdiff_t>(i0), a + static_cast<std::ptrdiff_t>(i1),
                 b + static_cast<std::ptrdiff_t>(k0 - i0), b + static_cast<std::ptrdiff_t>(k1 - i1),
                 merged.begin() + static_cast<std::ptrdiff_t>(k0));
    });
    items.swap(merged);
  }
}

}  // namespace membrane

#endif  // MEMBRANE_CORE_BASE_SPLIT_SORT_H_

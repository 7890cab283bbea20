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

// Sets items[i] = make(i) for every i of `items` (sized by the caller) and sorts them
// ascending. With threads > 1 and at least kMinSplitItems items, each half is made and sorted on
// a thread of its own and the halves are merged (a second buffer of the items' size while
// merging). The items must be unique (no two compare equal): the result is then the one
// std::sort gives, for any thread count. `make` is called from several threads at once.
template <typename T, typename Make>
void MakeAndSortUnique(std::vector<T>& items, int threads, Make make) {
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
    std::vector<T> merged(n);
    std::merge(items.begin(), items.begin() + static_cast<std::ptrdiff_t>(middle),
               items.begin() + static_cast<std::ptrdiff_t>(middle), items.end(), merged.begin());
    items = std::move(merged);
  }
}

}  // namespace membrane

#endif  // MEMBRANE_CORE_BASE_SPLIT_SORT_H_

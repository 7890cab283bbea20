// The placement step of a counting sort whose counts were made in parts (one per task), for
// the passes that group items by bucket on threads (formula (1)'s distinct count, the point
// index's rows).
#ifndef MEMBRANE_CORE_BASE_BUCKET_OFFSETS_H_
#define MEMBRANE_CORE_BASE_BUCKET_OFFSETS_H_

#include <cstddef>
#include <vector>

namespace membrane {

// counts[part][bucket] holds how many of the part's items fall in the bucket (every part with
// as many buckets). On return it holds the index of the part's first item of that bucket in
// an array grouped by bucket, buckets in order and within a bucket the parts in order, so
// that each part can then place its items without touching another's indices. Returns the
// buckets' starts in that array: one more entry than buckets, the last the total.
template <typename Count>
std::vector<Count> PlaceBucketsByPart(std::vector<std::vector<Count>>& counts) {
  const size_t buckets = counts.empty() ? 0 : counts.front().size();
  std::vector<Count> start(buckets + 1);
  Count next = 0;
  for (size_t b = 0; b < buckets; ++b) {
    start[b] = next;
    for (std::vector<Count>& part : counts) {
      const Count count = part[b];
      part[b] = next;
      next += count;
    }
  }
  start[buckets] = next;
  return start;
}

}  // namespace membrane

#endif  // MEMBRANE_CORE_BASE_BUCKET_OFFSETS_H_

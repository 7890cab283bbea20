// Bytes that a job keeps after its run, in pages mapped for them alone, outside malloc's heap.
//
// membraned's malloc keeps what a run frees in its one heap for the run's next stage
// (core/base/malloc_policy.h). A block allocated while a run's arrays are freed and kept after
// the run (an event of its late stages, its result) lands in the middle of that freed space
// and splits it, so that the next job's arrays, which would have fitted whole, take fresh
// pages beside the freed ones: a job after another peaked 1.4-3.1 GB higher than alone
// (docs/memory-decisions.md, "What a job keeps lives outside the heap").
#ifndef MEMBRANE_SERVER_MAPPED_BYTES_H_
#define MEMBRANE_SERVER_MAPPED_BYTES_H_

#include <cstddef>
#include <string>

#include "absl/strings/string_view.h"

namespace membrane::server {

class MappedBytes {
 public:
  MappedBytes() = default;
  ~MappedBytes();
  MappedBytes(MappedBytes&& other) noexcept;
  MappedBytes& operator=(MappedBytes&& other) noexcept;
  MappedBytes(const MappedBytes&) = delete;
  MappedBytes& operator=(const MappedBytes&) = delete;

  // Returns `size` bytes appended at the end, uninitialized, for the caller to fill before any
  // other call. The mapping grows by doubling (mremap, without a copy through the heap); where
  // the system refuses a mapping (its count of mappings at vm.max_map_count, say), the bytes
  // move to malloc's heap and stay there: the same contents, only placed as any block is.
  char* Extend(size_t size);

  // Appends `bytes`.
  void Append(absl::string_view bytes);

  absl::string_view view() const;
  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  // Whether the bytes lie in a mapping of their own (false once moved to the heap, and while
  // empty).
  bool mapped() const { return mapped_ != nullptr; }

 private:
  void Release();

  char* mapped_ = nullptr;  // the mapping, or null
  size_t capacity_ = 0;     // bytes mapped
  size_t size_ = 0;         // bytes used, in the mapping or in heap_
  std::string heap_;        // the bytes when no mapping could be had
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_MAPPED_BYTES_H_

// An allocator for large bit-planes that asks Linux for transparent huge pages.
//
// A shrink of a 70 M voxel grid touches about 40 planes of 9 MB each for the first time, and
// on a virtual machine the 4 KB page faults cost about a third of the shrink (measured with
// perf on the tall grid: the kernel's fault path and the zeroing memset). Blocks of at least
// kHugePageBytes are aligned to a huge page and advised MADV_HUGEPAGE, so the kernel maps
// them 2 MB at a time where it can (the machine's THP mode is usually "madvise"). Smaller
// blocks, and other systems, get plain operator new memory. An allocator made with a
// PlaneArena takes its blocks from the arena while it has room.
#ifndef MEMBRANE_CORE_ENGINE_HUGE_PAGE_ALLOCATOR_H_
#define MEMBRANE_CORE_ENGINE_HUGE_PAGE_ALLOCATOR_H_

#include <cstddef>
#include <cstdint>
#include <new>
#include <utility>

#include "core/engine/plane_arena.h"
#include "core/engine/unset_construct.h"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace membrane {

inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;

template <typename T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  // Takes blocks from `arena` (may be null: none), which must outlive every block taken.
  explicit HugePageAllocator(PlaneArena* arena) : arena_(arena) {}
  template <typename U>
  HugePageAllocator(const HugePageAllocator<U>& other) : arena_(other.arena()) {}

  // Uninitialized memory for `count` objects, failing as std::allocator does.
  T* allocate(std::size_t count) {
    // As std::allocator: a count past the largest object (less a huge page, for the rounding
    // below) fails before any size is computed from it, so that no size wraps (and the
    // compiler sees no larger size reach operator new).
    if (count > (static_cast<std::size_t>(PTRDIFF_MAX) - kHugePageBytes) / sizeof(T)) {
      throw std::bad_array_new_length();
    }
    const std::size_t bytes = count * sizeof(T);
    if (arena_ != nullptr) {
      if (void* p = arena_->Take(bytes)) return static_cast<T*>(p);
    }
    if (bytes < kHugePageBytes) return static_cast<T*>(::operator new(bytes));
    const std::size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
    void* p = ::operator new(rounded, std::align_val_t{kHugePageBytes});
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    madvise(p, rounded, MADV_HUGEPAGE);  // advice only: failure leaves 4 KB pages
#endif
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t count) {
    if (arena_ != nullptr && arena_->Owns(p)) return;  // freed with the arena
    const std::size_t bytes = count * sizeof(T);
    if (bytes < kHugePageBytes) {
      ::operator delete(p);
    } else {
      ::operator delete(p, std::align_val_t{kHugePageBytes});
    }
  }
  // Equal when they share the arena (or both have none): only then may one free the
  // other's blocks, so containers copy rather than steal across arenas.
  template <typename U>
  bool operator==(const HugePageAllocator<U>& other) const { return arena_ == other.arena(); }

  PlaneArena* arena() const { return arena_; }

 private:
  PlaneArena* arena_ = nullptr;
};

// A HugePageAllocator whose containers' size constructors and resize(n) leave the new elements
// unset, for big arrays whose every element is written before it is read (unset_construct.h).
template <typename T>
using UnfilledAllocator = UnsetConstruct<HugePageAllocator<T>>;

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_HUGE_PAGE_ALLOCATOR_H_

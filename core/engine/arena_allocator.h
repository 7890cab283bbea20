// An allocator for big arrays: blocks from a PlaneArena while it has room, else operator new.
//
// No page advice of its own: its blocks take the pages of the process's heap, which the
// executables have glibc advise for transparent huge pages (core/base/malloc_policy.h,
// docs/engine-decisions.md "Big arrays take the heap's pages"). Blocks of a page and more
// start on a cache line, as the arena's blocks do (PlaneArena::kBlockAlignment).
#ifndef MEMBRANE_CORE_ENGINE_ARENA_ALLOCATOR_H_
#define MEMBRANE_CORE_ENGINE_ARENA_ALLOCATOR_H_

#include <cstddef>
#include <cstdint>
#include <new>

#include "core/engine/plane_arena.h"
#include "core/engine/unset_construct.h"

namespace membrane {

inline constexpr std::size_t kAlignedBlockBytes = 4096;  // a page

template <typename T>
struct ArenaAllocator {
  using value_type = T;
  ArenaAllocator() = default;
  // Takes blocks from `arena` (may be null: none), which must outlive every block taken.
  explicit ArenaAllocator(PlaneArena* arena) : arena_(arena) {}
  template <typename U>
  ArenaAllocator(const ArenaAllocator<U>& other) : arena_(other.arena()) {}

  // Uninitialized memory for `count` objects, failing as std::allocator does.
  T* allocate(std::size_t count) {
    // As std::allocator: a count past the largest object fails before any size is computed
    // from it, so that no size wraps (and the compiler sees no larger size reach operator new).
    if (count > static_cast<std::size_t>(PTRDIFF_MAX) / sizeof(T)) {
      throw std::bad_array_new_length();
    }
    const std::size_t bytes = count * sizeof(T);
    if (arena_ != nullptr) {
      if (void* p = arena_->Take(bytes)) return static_cast<T*>(p);
    }
    if (bytes < kAlignedBlockBytes) return static_cast<T*>(::operator new(bytes));
    return static_cast<T*>(::operator new(bytes, std::align_val_t{PlaneArena::kBlockAlignment}));
  }
  void deallocate(T* p, std::size_t count) {
    if (arena_ != nullptr && arena_->Owns(p)) return;  // freed with the arena
    const std::size_t bytes = count * sizeof(T);
    if (bytes < kAlignedBlockBytes) {
      ::operator delete(p);
    } else {
      ::operator delete(p, std::align_val_t{PlaneArena::kBlockAlignment});
    }
  }
  // Equal when they share the arena (or both have none): only then may one free the
  // other's blocks, so containers copy rather than steal across arenas.
  template <typename U>
  bool operator==(const ArenaAllocator<U>& other) const { return arena_ == other.arena(); }

  PlaneArena* arena() const { return arena_; }

 private:
  PlaneArena* arena_ = nullptr;
};

// An ArenaAllocator whose containers' size constructors and resize(n) leave the new elements
// unset, for big arrays whose every element is written before it is read (unset_construct.h).
template <typename T>
using UnfilledAllocator = UnsetConstruct<ArenaAllocator<T>>;

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_ARENA_ALLOCATOR_H_

// One block of memory on transparent huge pages that the work planes of a shrink are cut from.
//
// The teapot-class grid (1.4 M voxels) has planes of 177 KB: too small for a huge page each,
// so each of the 21 work planes would be 43 fresh 4 KB pages, and on this VM those faults
// take 9 ms of a 110 ms shrink (measured). Cut from one block aligned to and advised for huge
// pages, the 21 planes fault two 2 MB pages instead. Memory is taken in order and given back
// only when the arena is destroyed.
#ifndef MEMBRANE_CORE_ENGINE_PLANE_ARENA_H_
#define MEMBRANE_CORE_ENGINE_PLANE_ARENA_H_

#include <cstddef>
#include <cstdint>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace membrane {

class PlaneArena {
 public:
  static constexpr std::size_t kAlignment = std::size_t{2} << 20;  // a huge page
  static constexpr std::size_t kBlockAlignment = 64;                // a cache line

  // Reserves `capacity` bytes (rounded up to a huge page; nothing is touched, so pages are
  // only resident once used). Fails as operator new does.
  explicit PlaneArena(std::size_t capacity)
      : capacity_((capacity + kAlignment - 1) / kAlignment * kAlignment) {
    if (capacity_ == 0) return;
    base_ = static_cast<char*>(::operator new(capacity_, std::align_val_t{kAlignment}));
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    madvise(base_, capacity_, MADV_HUGEPAGE);  // advice only: failure leaves 4 KB pages
#endif
  }
  ~PlaneArena() {
    if (base_ != nullptr) ::operator delete(base_, std::align_val_t{kAlignment});
  }
  PlaneArena(const PlaneArena&) = delete;
  PlaneArena& operator=(const PlaneArena&) = delete;

  // `bytes` of uninitialized memory aligned to kBlockAlignment, or nullptr when the arena
  // has no room left (the caller then allocates elsewhere).
  void* Take(std::size_t bytes) {
    const std::size_t size = (bytes + kBlockAlignment - 1) / kBlockAlignment * kBlockAlignment;
    if (size > capacity_ - used_) return nullptr;
    void* p = base_ + used_;
    used_ += size;
    return p;
  }
  // True when `p` was returned by Take (such memory must not be freed by anyone else).
  bool Owns(const void* p) const {
    const auto a = reinterpret_cast<std::uintptr_t>(p);
    const auto b = reinterpret_cast<std::uintptr_t>(base_);
    return base_ != nullptr && a >= b && a < b + capacity_;
  }
  std::size_t used() const { return used_; }
  std::size_t capacity() const { return capacity_; }

 private:
  std::size_t capacity_ = 0;
  std::size_t used_ = 0;
  char* base_ = nullptr;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_PLANE_ARENA_H_

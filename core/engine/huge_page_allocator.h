// An allocator for large bit-planes that asks Linux for transparent huge pages.
//
// A shrink of a 70 M voxel grid touches about 40 planes of 9 MB each for the first time, and
// on a virtual machine the 4 KB page faults cost about a third of the shrink (measured with
// perf on the tall grid: the kernel's fault path and the zeroing memset). Blocks of at least
// kHugePageBytes are aligned to a huge page and advised MADV_HUGEPAGE, so the kernel maps
// them 2 MB at a time where it can (the machine's THP mode is usually "madvise"). Smaller
// blocks, and other systems, get plain operator new memory.
#ifndef MEMBRANE_CORE_ENGINE_HUGE_PAGE_ALLOCATOR_H_
#define MEMBRANE_CORE_ENGINE_HUGE_PAGE_ALLOCATOR_H_

#include <cstddef>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace membrane {

inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;

template <typename T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <typename U>
  HugePageAllocator(const HugePageAllocator<U>&) {}

  // Uninitialized memory for `count` objects, failing as std::allocator does.
  T* allocate(std::size_t count) {
    const std::size_t bytes = count * sizeof(T);
    if (bytes < kHugePageBytes) return static_cast<T*>(::operator new(bytes));
    const std::size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
    void* p = ::operator new(rounded, std::align_val_t{kHugePageBytes});
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    madvise(p, rounded, MADV_HUGEPAGE);  // advice only: failure leaves 4 KB pages
#endif
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t count) {
    const std::size_t bytes = count * sizeof(T);
    if (bytes < kHugePageBytes) {
      ::operator delete(p);
    } else {
      ::operator delete(p, std::align_val_t{kHugePageBytes});
    }
  }
  template <typename U>
  bool operator==(const HugePageAllocator<U>&) const { return true; }
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_HUGE_PAGE_ALLOCATOR_H_

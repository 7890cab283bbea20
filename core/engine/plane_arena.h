// One block of memory that the work planes of a shrink are cut from.
//
// A shrink makes its planes once and reuses them through every generation: one allocation
// for all of them instead of one each (21 on the teapot-class grid, 8 planes of 271 MB each on
// a 10M-point torus), freed together. Memory is taken in order and given back only when the
// arena is destroyed; pages become resident as they are first written.
#ifndef MEMBRANE_CORE_ENGINE_PLANE_ARENA_H_
#define MEMBRANE_CORE_ENGINE_PLANE_ARENA_H_

#include <cstddef>
#include <cstdint>
#include <new>

namespace membrane {

class PlaneArena {
 public:
  static constexpr std::size_t kBlockAlignment = 64;  // a cache line

  // Reserves `capacity` bytes (rounded up to kBlockAlignment; nothing is touched, so pages
  // are only resident once used). Fails as operator new does.
  explicit PlaneArena(std::size_t capacity)
      : capacity_((capacity + kBlockAlignment - 1) / kBlockAlignment * kBlockAlignment) {
    if (capacity_ == 0) return;
    base_ = static_cast<char*>(::operator new(capacity_, std::align_val_t{kBlockAlignment}));
  }
  ~PlaneArena() {
    if (base_ != nullptr) ::operator delete(base_, std::align_val_t{kBlockAlignment});
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

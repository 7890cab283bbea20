#include "server/mapped_bytes.h"

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <utility>

namespace membrane::server {
namespace {

size_t PageBytes() {
  const long page = sysconf(_SC_PAGESIZE);
  return page > 0 ? static_cast<size_t>(page) : 4096;
}

}  // namespace

MappedBytes::~MappedBytes() { Release(); }

MappedBytes::MappedBytes(MappedBytes&& other) noexcept
    : mapped_(std::exchange(other.mapped_, nullptr)),
      capacity_(std::exchange(other.capacity_, 0)),
      size_(std::exchange(other.size_, 0)),
      heap_(std::move(other.heap_)) {
  other.heap_.clear();
}

MappedBytes& MappedBytes::operator=(MappedBytes&& other) noexcept {
  if (this != &other) {
    Release();
    mapped_ = std::exchange(other.mapped_, nullptr);
    capacity_ = std::exchange(other.capacity_, 0);
    size_ = std::exchange(other.size_, 0);
    heap_ = std::move(other.heap_);
    other.heap_.clear();
  }
  return *this;
}

void MappedBytes::Release() {
  if (mapped_ != nullptr) munmap(mapped_, capacity_);
  mapped_ = nullptr;
  capacity_ = 0;
  size_ = 0;
  heap_.clear();
  heap_.shrink_to_fit();
}

char* MappedBytes::Extend(size_t size) {
  const size_t at = size_;
  const size_t needed = size_ + size;
  const bool in_heap = mapped_ == nullptr && size_ > 0;
  if (!in_heap && needed > capacity_) {
    const size_t page = PageBytes();
    size_t grown = std::max(capacity_ * 2, page);
    while (grown < needed) grown *= 2;
    void* to = mapped_ == nullptr
                   ? mmap(nullptr, grown, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS,
                          -1, 0)
                   : mremap(mapped_, capacity_, grown, MREMAP_MAYMOVE);
    if (to != MAP_FAILED) {
      mapped_ = static_cast<char*>(to);
      capacity_ = grown;
    } else {
      // The heap holds them from now on; the mapping, if any, goes.
      heap_.reserve(needed);
      heap_.assign(mapped_ == nullptr ? "" : mapped_, size_);
      if (mapped_ != nullptr) munmap(mapped_, capacity_);
      mapped_ = nullptr;
      capacity_ = 0;
    }
  }
  size_ = needed;
  if (mapped_ != nullptr) return mapped_ + at;
  heap_.resize(needed);
  return heap_.data() + at;
}

void MappedBytes::Append(absl::string_view bytes) {
  if (bytes.empty()) return;
  std::memcpy(Extend(bytes.size()), bytes.data(), bytes.size());
}

absl::string_view MappedBytes::view() const {
  if (mapped_ != nullptr) return absl::string_view(mapped_, size_);
  return absl::string_view(heap_.data(), size_);
}

}  // namespace membrane::server

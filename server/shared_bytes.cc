#include "server/shared_bytes.h"

#include <sys/mman.h>

#include <cstring>
#include <new>
#include <utility>

namespace membrane::server {

SharedBytes SharedBytes::Copy(absl::string_view bytes) {
  if (bytes.empty()) return SharedBytes();
  const size_t total = sizeof(Header) + bytes.size();
  void* at = mmap(nullptr, total, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  size_t mapped_bytes = total;
  if (at == MAP_FAILED) {
    at = ::operator new(total);  // fails as any allocation of the process would
    mapped_bytes = 0;
  }
  Header* header = new (at) Header{{1}, bytes.size(), mapped_bytes};
  std::memcpy(reinterpret_cast<char*>(header + 1), bytes.data(), bytes.size());
  return SharedBytes(header);
}

SharedBytes::SharedBytes(const SharedBytes& other) noexcept : header_(other.header_) {
  if (header_ != nullptr) header_->owners.fetch_add(1, std::memory_order_relaxed);
}

SharedBytes& SharedBytes::operator=(const SharedBytes& other) noexcept {
  if (this != &other) {
    if (other.header_ != nullptr) other.header_->owners.fetch_add(1, std::memory_order_relaxed);
    Drop();
    header_ = other.header_;
  }
  return *this;
}

SharedBytes::SharedBytes(SharedBytes&& other) noexcept
    : header_(std::exchange(other.header_, nullptr)) {}

SharedBytes& SharedBytes::operator=(SharedBytes&& other) noexcept {
  if (this != &other) {
    Drop();
    header_ = std::exchange(other.header_, nullptr);
  }
  return *this;
}

SharedBytes::~SharedBytes() { Drop(); }

void SharedBytes::Drop() {
  Header* header = std::exchange(header_, nullptr);
  if (header == nullptr || header->owners.fetch_sub(1, std::memory_order_acq_rel) != 1) return;
  const size_t mapped_bytes = header->mapped_bytes;
  header->~Header();
  if (mapped_bytes != 0) {
    munmap(header, mapped_bytes);
  } else {
    ::operator delete(header);
  }
}

absl::string_view SharedBytes::view() const {
  if (header_ == nullptr) return absl::string_view();
  return absl::string_view(reinterpret_cast<const char*>(header_ + 1), header_->size);
}

size_t SharedBytes::size() const { return header_ == nullptr ? 0 : header_->size; }

bool SharedBytes::mapped() const { return header_ != nullptr && header_->mapped_bytes != 0; }

}  // namespace membrane::server

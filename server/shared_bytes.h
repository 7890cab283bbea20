// Immutable bytes shared without a copy (a job's mesh, its preview), in pages mapped for them
// alone with their count of owners, so that keeping them allocates nothing in malloc's heap
// (server/mapped_bytes.h says why).
#ifndef MEMBRANE_SERVER_SHARED_BYTES_H_
#define MEMBRANE_SERVER_SHARED_BYTES_H_

#include <atomic>
#include <cstddef>
#include <cstdint>

#include "absl/strings/string_view.h"

namespace membrane::server {

class SharedBytes {
 public:
  // No bytes; allocates nothing.
  SharedBytes() = default;

  // A copy of `bytes` in a mapping of its own, or in one block of the heap where the system
  // refuses a mapping (as MappedBytes). Empty `bytes` give an empty SharedBytes.
  static SharedBytes Copy(absl::string_view bytes);

  // Copies share the bytes (one more owner); the last owner to go unmaps them.
  SharedBytes(const SharedBytes& other) noexcept;
  SharedBytes& operator=(const SharedBytes& other) noexcept;
  SharedBytes(SharedBytes&& other) noexcept;
  SharedBytes& operator=(SharedBytes&& other) noexcept;
  ~SharedBytes();

  absl::string_view view() const;
  size_t size() const;
  bool empty() const { return size() == 0; }
  // Whether the bytes lie in a mapping of their own.
  bool mapped() const;

 private:
  struct Header {
    std::atomic<int64_t> owners;
    size_t size;
    size_t mapped_bytes;  // of the mapping holding header and bytes; 0: one block of the heap
  };
  explicit SharedBytes(Header* header) : header_(header) {}
  void Drop();

  Header* header_ = nullptr;  // followed by the bytes
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_SHARED_BYTES_H_

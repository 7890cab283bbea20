#include "server/upload_memory.h"

#include <utility>

#include "absl/strings/str_format.h"

namespace membrane::server {

UploadMemory::Hold::Hold(Hold&& other) noexcept
    : owner_(std::exchange(other.owner_, nullptr)), bytes_(std::exchange(other.bytes_, 0)) {}

UploadMemory::Hold& UploadMemory::Hold::operator=(Hold&& other) noexcept {
  if (this != &other) {
    Release();
    owner_ = std::exchange(other.owner_, nullptr);
    bytes_ = std::exchange(other.bytes_, 0);
  }
  return *this;
}

void UploadMemory::Hold::Release() {
  if (owner_ != nullptr) owner_->Give(bytes_);
  owner_ = nullptr;
  bytes_ = 0;
}

absl::StatusOr<UploadMemory::Hold> UploadMemory::Reserve(int64_t bytes) {
  absl::MutexLock lock(&mutex_);
  if (!Fits(bytes)) {
    return absl::ResourceExhaustedError(absl::StrFormat(
        "an upload of %d bytes is over the server's memory for uploads, %d bytes "
        "(--upload-memory-bytes)",
        bytes, total_));
  }
  if (total_ > 0 && held_ + bytes > total_) {
    return absl::ResourceExhaustedError(absl::StrFormat(
        "the server is busy: an upload of %d bytes does not fit beside the %d bytes of uploads "
        "it holds, within its %d bytes for uploads (--upload-memory-bytes)",
        bytes, held_, total_));
  }
  held_ += bytes;
  return Hold(this, bytes);
}

int64_t UploadMemory::held() const {
  absl::MutexLock lock(&mutex_);
  return held_;
}

void UploadMemory::Give(int64_t bytes) {
  absl::MutexLock lock(&mutex_);
  held_ -= bytes;
}

int64_t DefaultUploadMemory(int64_t total_bytes) { return total_bytes > 0 ? total_bytes / 8 : 0; }

}  // namespace membrane::server

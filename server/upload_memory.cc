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

absl::Status UploadMemory::CheckFits(int64_t bytes) const {
  if (total_ <= 0 || bytes <= total_) return absl::OkStatus();
  return absl::ResourceExhaustedError(absl::StrFormat(
      "an upload of %d bytes is over the server's memory for uploads, %d bytes "
      "(--upload-memory-bytes)",
      bytes, total_));
}

absl::Status UploadMemory::Grow(Hold& hold, int64_t bytes) {
  absl::MutexLock lock(&mutex_);
  if (total_ > 0 && held_ + bytes > total_) {
    return absl::ResourceExhaustedError(absl::StrFormat(
        "the server is busy: %d more bytes of upload do not fit beside the %d bytes of uploads "
        "it holds, within its %d bytes for uploads (--upload-memory-bytes)",
        bytes, held_, total_));
  }
  held_ += bytes;
  hold.owner_ = this;
  hold.bytes_ += bytes;
  return absl::OkStatus();
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

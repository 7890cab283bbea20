#include "server/memory_budget.h"

#include "absl/strings/str_format.h"
#include "absl/time/time.h"
#include "core/geometry/point_cloud.h"

namespace membrane::server {
namespace {

// Measured on the bench clouds: the grid (1 byte per voxel) plus the shrinker's bitsets,
// snapshots and the surface's index maps stay under 6 bytes per voxel.
constexpr int64_t kBytesPerVoxel = 6;
// The decoded cloud, the pipeline's copy for the surface fit, and slack for the mesh.
constexpr int64_t kBytesPerPoint = 4 * sizeof(Point3f);

}  // namespace

int64_t EstimateJobBytes(int64_t voxels, int64_t points) {
  return voxels * kBytesPerVoxel + points * kBytesPerPoint;
}

absl::Status MemoryBudget::Reserve(int64_t bytes, const CancelToken& cancel) {
  if (total_ <= 0) return absl::OkStatus();
  if (bytes > total_) {
    return absl::ResourceExhaustedError(absl::StrFormat(
        "the job needs about %d bytes, over the server's memory budget of %d bytes; use a "
        "larger voxel_size",
        bytes, total_));
  }
  absl::MutexLock lock(&mutex_);
  auto fits = [this, bytes]() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_) {
    return reserved_ + bytes <= total_;
  };
  while (!mutex_.AwaitWithTimeout(absl::Condition(&fits), absl::Milliseconds(50))) {
    if (cancel.cancelled()) return absl::CancelledError("cancelled while waiting for memory");
  }
  reserved_ += bytes;
  return absl::OkStatus();
}

void MemoryBudget::Release(int64_t bytes) {
  if (total_ <= 0) return;
  absl::MutexLock lock(&mutex_);
  reserved_ -= bytes;
}

}  // namespace membrane::server

#include "tests/server/faulty_store_files.h"

#include <utility>
#include <vector>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"

namespace membrane::testing {
namespace {

class FaultyFiles final : public server::StoreFiles {
 public:
  explicit FaultyFiles(std::shared_ptr<DiskFaults> faults)
      : faults_(std::move(faults)), real_(server::PosixStoreFiles()) {}

  absl::Status MakeDirectory(const std::string& dir) override {
    return real_->MakeDirectory(dir);
  }
  absl::StatusOr<std::vector<std::string>> List(const std::string& dir) override {
    return real_->List(dir);
  }
  absl::StatusOr<std::string> Read(const std::string& path, int64_t max_bytes) override {
    return real_->Read(path, max_bytes);
  }
  absl::Status Remove(const std::string& path) override { return real_->Remove(path); }

  absl::Status Write(const std::string& dir, const std::string& path,
                     absl::Span<const absl::string_view> pieces) override {
    if (absl::EndsWith(path, ".job")) {
      absl::MutexLock lock(&faults_->mutex);
      if (faults_->hold_records && faults_->passing_records > 0) {
        --faults_->passing_records;
      } else {
        ++faults_->held;
        faults_->mutex.Await(absl::Condition(
            +[](DiskFaults* f)
                ABSL_EXCLUSIVE_LOCKS_REQUIRED(f->mutex) { return !f->hold_records; },
            faults_.get()));
        --faults_->held;
      }
    }
    int64_t bytes = 0;
    for (const absl::string_view piece : pieces) bytes += static_cast<int64_t>(piece.size());
    const int64_t free_bytes = faults_->free_bytes.load();
    if (faults_->read_only.load()) {
      ++faults_->failed_writes;
      return absl::UnavailableError(absl::StrCat(path, ".tmp: Read-only file system"));
    }
    if (free_bytes >= 0 && bytes > free_bytes) {
      ++faults_->failed_writes;
      return absl::UnavailableError(absl::StrCat(path, ".tmp: No space left on device"));
    }
    return real_->Write(dir, path, pieces);
  }

 private:
  const std::shared_ptr<DiskFaults> faults_;
  const std::unique_ptr<server::StoreFiles> real_;
};

}  // namespace

std::unique_ptr<server::StoreFiles> FaultyStoreFiles(std::shared_ptr<DiskFaults> faults) {
  return std::make_unique<FaultyFiles>(std::move(faults));
}

}  // namespace membrane::testing

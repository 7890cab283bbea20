// StoreFiles on the real file system whose writes a test can make fail as a read-only or a
// full disk does, without mounting one.
#ifndef MEMBRANE_TESTS_SERVER_FAULTY_STORE_FILES_H_
#define MEMBRANE_TESTS_SERVER_FAULTY_STORE_FILES_H_

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "absl/synchronization/mutex.h"
#include "server/store_files.h"

namespace membrane::testing {

// What the test changes while the store runs; shared with the files it made.
struct DiskFaults {
  // Every write fails with EROFS, as on a file system remounted read-only.
  std::atomic<bool> read_only{false};
  // Writes of more bytes than this fail with ENOSPC, as on a nearly full disk; -1: none do.
  std::atomic<int64_t> free_bytes{-1};
  // Writes that failed so far.
  std::atomic<int> failed_writes{0};
  // While true, writes of *.job records wait (for a test that looks between a job's end and
  // its record); set to false to let them through.
  absl::Mutex mutex;
  bool hold_records ABSL_GUARDED_BY(mutex) = false;
  // While hold_records, this many more *.job writes go through before the next one waits (the
  // record that accepts a job, for a test that holds the record of its end).
  int passing_records ABSL_GUARDED_BY(mutex) = 0;
  int held ABSL_GUARDED_BY(mutex) = 0;  // writes waiting now
};

// PosixStoreFiles, failing as `faults` says.
std::unique_ptr<server::StoreFiles> FaultyStoreFiles(std::shared_ptr<DiskFaults> faults);

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_SERVER_FAULTY_STORE_FILES_H_

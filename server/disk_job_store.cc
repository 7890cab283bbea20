#include "server/disk_job_store.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <utility>

#include <google/protobuf/io/zero_copy_stream_impl_lite.h>
#include <google/protobuf/util/delimited_message_util.h>

#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "core/io/file_bytes.h"
#include "proto/crc32c.h"
#include "server/rpc_status.h"
#include "server/server_log.h"

namespace membrane::server {
namespace {

constexpr char kSuffix[] = ".job";
constexpr size_t kChunkBytes = 1 << 20;

std::string ErrnoText() { return std::strerror(errno); }

// Writes `bytes` to `path` so that a crash leaves the old file or the new one, never a mix:
// a temporary file, fsync, rename over `path`, fsync of the directory.
absl::Status WriteDurably(const std::string& dir, const std::string& path,
                          const std::string& bytes) {
  const std::string temporary = path + ".tmp";
  const int fd = open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0) return absl::UnavailableError(absl::StrCat(temporary, ": ", ErrnoText()));
  size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string error = ErrnoText();
      close(fd);
      unlink(temporary.c_str());
      return absl::UnavailableError(absl::StrCat(temporary, ": ", error));
    }
    written += static_cast<size_t>(n);
  }
  const bool synced = fsync(fd) == 0;
  const std::string sync_error = synced ? "" : ErrnoText();
  close(fd);
  if (!synced || rename(temporary.c_str(), path.c_str()) != 0) {
    const std::string error = synced ? ErrnoText() : sync_error;
    unlink(temporary.c_str());
    return absl::UnavailableError(absl::StrCat(path, ": ", error));
  }
  if (const int dir_fd = open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dir_fd >= 0) {
    fsync(dir_fd);
    close(dir_fd);
  }
  return absl::OkStatus();
}

// The job a record describes: finished as it was, or, without a JobDone (the process stopped
// first), FAILED as of `now`; `interrupted` says which.
absl::StatusOr<std::shared_ptr<Job>> ParseRecord(const std::string& bytes, absl::Time now,
                                                 bool& interrupted) {
  google::protobuf::io::ArrayInputStream input(bytes.data(), static_cast<int>(bytes.size()));
  v1::Job snapshot;
  bool clean_eof = false;
  if (!google::protobuf::util::ParseDelimitedFromZeroCopyStream(&snapshot, &input, &clean_eof)) {
    return absl::DataLossError("no job snapshot at its start");
  }
  std::vector<v1::JobEvent> events;
  std::string statistics, mesh;
  v1::MeshSummary summary;
  const v1::ResultHeader* result = nullptr;
  v1::ResultHeader header;
  const v1::JobDone* done = nullptr;
  v1::JobDone done_event;
  for (;;) {
    v1::JobEvent event;
    if (!google::protobuf::util::ParseDelimitedFromZeroCopyStream(&event, &input, &clean_eof)) {
      if (clean_eof) break;
      return absl::DataLossError("an event is truncated or corrupted");
    }
    if (done != nullptr) return absl::DataLossError("events after JobDone");
    switch (event.event_case()) {
      case v1::JobEvent::kStage:
      case v1::JobEvent::kGeneration: events.push_back(std::move(event)); break;
      case v1::JobEvent::kResult:
        header = event.result();
        result = &header;
        break;
      case v1::JobEvent::kMeshChunk: mesh += event.mesh_chunk(); break;
      case v1::JobEvent::kDone:
        done_event = event.done();
        done = &done_event;
        break;
      default: return absl::DataLossError("an event of an unknown kind");
    }
  }
  interrupted = done == nullptr;
  if (interrupted) {
    const std::string was = absl::AsciiStrToLower(v1::JobState_Name(snapshot.state()));
    *snapshot.mutable_error() = ToRpcStatus(absl::UnavailableError(absl::StrCat(
        "membraned stopped while the job was ", was,
        "; its upload was not kept: submit it again")));
    snapshot.set_state(v1::FAILED);
    snapshot.set_finished_unix_seconds(absl::ToDoubleSeconds(now - absl::UnixEpoch()));
    return Job::Restore(snapshot, std::move(events), "", {}, "");
  }
  if (done->state() == v1::SUCCEEDED) {
    if (result == nullptr) return absl::DataLossError("a SUCCEEDED job without its result");
    if (mesh.size() != result->mesh_bytes() || Crc32c(mesh) != result->mesh_crc32c()) {
      return absl::DataLossError("the mesh does not match its size and CRC-32C");
    }
    statistics = result->statistics_json();
    summary = result->mesh();
  }
  snapshot.set_state(done->state());
  *snapshot.mutable_error() = done->status();
  return Job::Restore(snapshot, std::move(events), std::move(statistics), std::move(summary),
                      std::move(mesh));
}

}  // namespace

DiskJobStore::DiskJobStore(std::string dir)
    : dir_(std::move(dir)), writer_([this] { WriterLoop(); }) {}

DiskJobStore::~DiskJobStore() {
  {
    absl::MutexLock lock(&mutex_);
    stopping_ = true;
  }
  writer_.join();
}

std::string DiskJobStore::PathOf(const std::string& id) const {
  return absl::StrCat(dir_, "/", id, kSuffix);
}

absl::StatusOr<int> DiskJobStore::Load() {
  if (mkdir(dir_.c_str(), 0700) != 0 && errno != EEXIST) {
    return absl::UnavailableError(
        absl::StrCat("cannot create the job store ", dir_, ": ", ErrnoText()));
  }
  DIR* listing = opendir(dir_.c_str());
  if (listing == nullptr) {
    return absl::UnavailableError(
        absl::StrCat("cannot read the job store ", dir_, ": ", ErrnoText()));
  }
  std::vector<std::string> names;
  while (const dirent* entry = readdir(listing)) names.emplace_back(entry->d_name);
  closedir(listing);
  const absl::Time now = absl::Now();
  std::vector<std::shared_ptr<Job>> jobs;
  std::vector<std::string> interrupted_ids;
  for (const std::string& name : names) {
    const std::string path = absl::StrCat(dir_, "/", name);
    // A write the process did not finish: the record before it stands.
    if (absl::EndsWith(name, ".tmp")) {
      unlink(path.c_str());
      continue;
    }
    if (!absl::EndsWith(name, kSuffix)) continue;
    const std::string id = name.substr(0, name.size() - std::strlen(kSuffix));
    absl::StatusOr<std::string> bytes = ReadFileBytes(path);
    bool interrupted = false;
    absl::StatusOr<std::shared_ptr<Job>> job =
        bytes.ok() ? ParseRecord(*bytes, now, interrupted) : bytes.status();
    if (job.ok() && (*job)->id() != id) {
      job = absl::DataLossError(absl::StrCat("it holds job '", (*job)->id(), "'"));
    }
    if (!job.ok()) {
      LogEvent("store_unreadable",
               {{"file", path}, {"message", std::string(job.status().message())}});
      continue;
    }
    if (interrupted) interrupted_ids.push_back(id);
    jobs.push_back(*std::move(job));
  }
  // Oldest first, as they were added.
  std::sort(jobs.begin(), jobs.end(), [](const auto& a, const auto& b) {
    return a->Snapshot().created_unix_seconds() < b->Snapshot().created_unix_seconds();
  });
  for (std::shared_ptr<Job>& job : jobs) memory_.Add(std::move(job));
  for (const std::string& id : interrupted_ids) Enqueue(id);
  LogEvent("store_loaded", {{"dir", dir_},
                            {"jobs", absl::StrCat(jobs.size())},
                            {"interrupted", absl::StrCat(interrupted_ids.size())}});
  return static_cast<int>(jobs.size());
}

void DiskJobStore::Add(std::shared_ptr<Job> job) {
  const std::string id = job->id();
  memory_.Add(std::move(job));
  WaitFor(Enqueue(id));
}

std::shared_ptr<Job> DiskJobStore::Find(const std::string& id) const { return memory_.Find(id); }

std::vector<std::shared_ptr<Job>> DiskJobStore::List() const { return memory_.List(); }

int DiskJobStore::RemoveFinishedBefore(absl::Time cutoff) {
  const std::vector<std::shared_ptr<Job>> expired = memory_.TakeFinishedBefore(cutoff);
  for (const std::shared_ptr<Job>& job : expired) unlink(PathOf(job->id()).c_str());
  return static_cast<int>(expired.size());
}

void DiskJobStore::Finished(const std::string& id) { Enqueue(id); }

int64_t DiskJobStore::Enqueue(const std::string& id) {
  absl::MutexLock lock(&mutex_);
  pending_.push_back(id);
  return ++asked_;
}

void DiskJobStore::Flush() {
  int64_t last = 0;
  {
    absl::MutexLock lock(&mutex_);
    last = asked_;
  }
  WaitFor(last);
}

void DiskJobStore::WaitFor(int64_t ticket) {
  // Writes run in the order asked for: once `done_` reaches the ticket, that one is done.
  absl::MutexLock lock(&mutex_);
  const auto written = [this, ticket]() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_) {
    return done_ >= ticket;
  };
  mutex_.Await(absl::Condition(&written));
}

void DiskJobStore::WriterLoop() {
  for (;;) {
    std::string id;
    {
      absl::MutexLock lock(&mutex_);
      const auto ready = [this]() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_) {
        return !pending_.empty() || stopping_;
      };
      mutex_.Await(absl::Condition(&ready));
      if (pending_.empty()) return;  // stopping, and everything written
      id = std::move(pending_.front());
      pending_.pop_front();
    }
    // The job as it is now: a later change enqueues another write, so the last write holds
    // the last state. A job expired meanwhile is not written back.
    if (const std::shared_ptr<Job> job = memory_.Find(id)) {
      if (absl::Status s = Write(*job); !s.ok()) {
        LogEvent("store_write_failed", {{"job", id}, {"message", std::string(s.message())}});
      }
    }
    absl::MutexLock lock(&mutex_);
    ++done_;
  }
}

absl::Status DiskJobStore::Write(const Job& job) const {
  // The closing events first: a job that ends in between then has a done snapshot and no
  // JobDone, which reads as interrupted until the write its end enqueued replaces it.
  const std::vector<v1::JobEvent> closing = job.ClosingEvents(kChunkBytes);
  const std::vector<v1::JobEvent> events = job.Events();
  const v1::Job snapshot = job.Snapshot();
  std::string bytes;
  {
    google::protobuf::io::StringOutputStream output(&bytes);
    bool ok = google::protobuf::util::SerializeDelimitedToZeroCopyStream(snapshot, &output);
    for (const auto* list : {&events, &closing})
      for (const v1::JobEvent& event : *list)
        ok = ok && google::protobuf::util::SerializeDelimitedToZeroCopyStream(event, &output);
    if (!ok) return absl::InternalError("cannot serialize the job");
  }
  return WriteDurably(dir_, PathOf(job.id()), bytes);
}

}  // namespace membrane::server

#include "server/disk_job_store.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <set>
#include <utility>

#include <google/protobuf/io/zero_copy_stream_impl_lite.h>
#include <google/protobuf/util/delimited_message_util.h>

#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "core/io/draco_parts.h"
#include "proto/crc32c.h"
#include "server/rpc_status.h"
#include "server/server_log.h"

namespace membrane::server {
namespace {

constexpr char kSuffix[] = ".job";
constexpr char kUploadSuffix[] = ".upload";
constexpr char kWriteCheck[] = ".write-check";
constexpr size_t kChunkBytes = 1 << 20;
// The header of an upload file: a delimited UploadHeader of two small fields and the parts'
// sizes (at most kMaxDracoParts varints of at most 10 bytes, packed).
constexpr int64_t kUploadHeaderBytes = 64 + 10 * kMaxDracoParts;

// What a record holds. Without a JobDone (`ended` false), the process stopped first.
struct Record {
  v1::Job snapshot;
  std::vector<v1::JobEvent> events;
  bool ended = false;
  v1::JobDone done;
  std::string statistics;
  v1::MeshSummary summary;
  std::string mesh;
};

absl::StatusOr<Record> ParseRecord(const std::string& bytes) {
  google::protobuf::io::ArrayInputStream input(bytes.data(), static_cast<int>(bytes.size()));
  Record record;
  bool clean_eof = false;
  if (!google::protobuf::util::ParseDelimitedFromZeroCopyStream(&record.snapshot, &input,
                                                                &clean_eof)) {
    return absl::DataLossError("no job snapshot at its start");
  }
  const v1::ResultHeader* result = nullptr;
  v1::ResultHeader header;
  for (;;) {
    v1::JobEvent event;
    if (!google::protobuf::util::ParseDelimitedFromZeroCopyStream(&event, &input, &clean_eof)) {
      if (clean_eof) break;
      return absl::DataLossError("an event is truncated or corrupted");
    }
    if (record.ended) return absl::DataLossError("events after JobDone");
    switch (event.event_case()) {
      case v1::JobEvent::kStage:
      case v1::JobEvent::kGeneration:
      case v1::JobEvent::kProgress: record.events.push_back(std::move(event)); break;
      case v1::JobEvent::kResult:
        header = event.result();
        result = &header;
        break;
      case v1::JobEvent::kMeshChunk: record.mesh += event.mesh_chunk(); break;
      case v1::JobEvent::kDone:
        record.done = event.done();
        record.ended = true;
        break;
      default: return absl::DataLossError("an event of an unknown kind");
    }
  }
  if (record.ended && record.done.state() == v1::SUCCEEDED) {
    if (result == nullptr) return absl::DataLossError("a SUCCEEDED job without its result");
    if (record.mesh.size() != result->mesh_bytes() ||
        Crc32c(record.mesh) != result->mesh_crc32c()) {
      return absl::DataLossError("the mesh does not match its size and CRC-32C");
    }
    record.statistics = result->statistics_json();
    record.summary = result->mesh();
  }
  return record;
}

// The upload an upload file holds, checked against its header and the job's record; its
// parts' sizes into `part_bytes`.
absl::StatusOr<std::string> ParseUpload(const std::string& bytes, uint64_t expected_bytes,
                                        std::vector<uint64_t>& part_bytes) {
  google::protobuf::io::ArrayInputStream input(bytes.data(), static_cast<int>(bytes.size()));
  v1::UploadHeader header;
  if (!google::protobuf::util::ParseDelimitedFromZeroCopyStream(&header, &input, nullptr)) {
    return absl::DataLossError("the upload's header is truncated or corrupted");
  }
  const std::string upload = bytes.substr(static_cast<size_t>(input.ByteCount()));
  if (upload.size() != header.upload_bytes() || upload.size() != expected_bytes ||
      Crc32c(upload) != header.upload_crc32c()) {
    return absl::DataLossError(absl::StrCat("the upload (", upload.size(),
                                            " bytes) does not match its size and CRC-32C"));
  }
  if (absl::Status s = CheckDracoPartBytes(header.upload_part_bytes(), upload.size()); !s.ok()) {
    return absl::DataLossError(absl::StrCat("the upload's header: ", s.message()));
  }
  part_bytes.assign(header.upload_part_bytes().begin(), header.upload_part_bytes().end());
  return upload;
}

// The job a finished record describes.
std::shared_ptr<Job> Ended(Record record) {
  record.snapshot.set_state(record.done.state());
  *record.snapshot.mutable_error() = record.done.status();
  return Job::Restore(record.snapshot, std::move(record.events), std::move(record.statistics),
                      std::move(record.summary), std::move(record.mesh));
}

// An unfinished job that cannot run again (its upload is unreadable): FAILED as of `now`.
std::shared_ptr<Job> Lost(Record record, absl::Time now, absl::string_view why) {
  const std::string was = absl::AsciiStrToLower(v1::JobState_Name(record.snapshot.state()));
  *record.snapshot.mutable_error() = ToRpcStatus(absl::UnavailableError(
      absl::StrCat("membraned stopped while the job was ", was, "; its upload could not be read (",
                   why, "): submit it again")));
  record.snapshot.set_state(v1::FAILED);
  record.snapshot.set_finished_unix_seconds(absl::ToDoubleSeconds(now - absl::UnixEpoch()));
  return Job::Restore(record.snapshot, std::move(record.events), "", {}, "");
}

}  // namespace

int64_t RecordBytesFor(int64_t max_mesh_bytes) {
  // The events of a 10M-point job of 20 minutes (1000-odd generations, a progress event a
  // second) are under 1 MB; the chunks' framing is a few bytes a MiB of mesh.
  constexpr int64_t kEventBytes = int64_t{16} << 20;
  return max_mesh_bytes + kEventBytes;
}

DiskJobStore::DiskJobStore(std::string dir, DiskJobStoreOptions options,
                           std::unique_ptr<StoreFiles> files)
    : dir_(std::move(dir)),
      options_(options),
      files_(std::move(files)),
      writer_([this] { WriterLoop(); }) {}

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

std::string DiskJobStore::UploadPathOf(const std::string& id) const {
  return absl::StrCat(dir_, "/", id, kUploadSuffix);
}

void DiskJobStore::SetWritableListener(std::function<void(bool writable)> listener) {
  absl::MutexLock lock(&listener_mutex_);
  listener_ = std::move(listener);
}

absl::StatusOr<DiskJobStore::Loaded> DiskJobStore::Load(const HookMaker& make_hook) {
  if (absl::Status s = files_->MakeDirectory(dir_); !s.ok()) {
    return absl::UnavailableError(absl::StrCat("cannot create the job store: ", s.message()));
  }
  // A store that cannot be written would accept nothing: better said at start-up.
  const std::string check = absl::StrCat(dir_, "/", kWriteCheck);
  const std::string page(4096, '\0');
  if (absl::Status s = files_->Write(dir_, check, {page}); !s.ok()) {
    return absl::UnavailableError(
        absl::StrCat("the job store ", dir_, " cannot be written: ", s.message()));
  }
  files_->Remove(check).IgnoreError();
  absl::StatusOr<std::vector<std::string>> names = files_->List(dir_);
  if (!names.ok()) {
    return absl::UnavailableError(absl::StrCat("cannot read the job store: ", names.status().message()));
  }
  std::set<std::string> uploads;  // ids with an upload file
  std::vector<std::string> records;
  for (const std::string& name : *names) {
    // A write the process did not finish: the file before it stands.
    if (absl::EndsWith(name, ".tmp")) {
      files_->Remove(absl::StrCat(dir_, "/", name)).IgnoreError();
    } else if (absl::EndsWith(name, kUploadSuffix)) {
      uploads.insert(name.substr(0, name.size() - std::strlen(kUploadSuffix)));
    } else if (absl::EndsWith(name, kSuffix)) {
      records.push_back(name.substr(0, name.size() - std::strlen(kSuffix)));
    }
  }
  const absl::Time now = absl::Now();
  std::vector<std::shared_ptr<Job>> jobs;
  std::vector<std::string> lost_ids;
  std::set<std::string> keep_uploads;  // of resumed jobs, and of records left for a person
  Loaded loaded;
  for (const std::string& id : records) {
    const std::string path = PathOf(id);
    absl::StatusOr<std::string> bytes = files_->Read(path, options_.max_record_bytes);
    absl::StatusOr<Record> record = bytes.ok() ? ParseRecord(*bytes) : bytes.status();
    if (record.ok() && record->snapshot.id() != id) {
      record = absl::DataLossError(absl::StrCat("it holds job '", record->snapshot.id(), "'"));
    }
    if (!record.ok()) {
      LogEvent("store_unreadable",
               {{"file", path}, {"message", std::string(record.status().message())}});
      keep_uploads.insert(id);
      continue;
    }
    if (record->ended) {
      jobs.push_back(Ended(*std::move(record)));
      continue;
    }
    absl::StatusOr<std::string> upload =
        uploads.contains(id)
            ? files_->Read(UploadPathOf(id), options_.max_upload_bytes + kUploadHeaderBytes)
            : absl::NotFoundError("no upload file");
    std::vector<uint64_t> part_bytes;
    if (upload.ok()) upload = ParseUpload(*upload, record->snapshot.upload_bytes(), part_bytes);
    if (!upload.ok()) {
      LogEvent("store_upload_unreadable",
               {{"job", id}, {"message", std::string(upload.status().message())}});
      lost_ids.push_back(id);
      jobs.push_back(Lost(*std::move(record), now, upload.status().message()));
      continue;
    }
    std::shared_ptr<Job> job = Job::Resume(record->snapshot, *std::move(upload), make_hook(id));
    job->set_upload_part_bytes(std::move(part_bytes));
    job->RequireEndRecord();
    keep_uploads.insert(id);
    loaded.resumed.push_back(job);
    jobs.push_back(std::move(job));
  }
  // An upload without a record (a crash inside Add: its client never heard of the job) or
  // whose job has ended (a crash before its removal).
  for (const std::string& id : uploads) {
    if (!keep_uploads.contains(id)) files_->Remove(UploadPathOf(id)).IgnoreError();
  }
  // Oldest first, as they were added.
  const auto older = [](const auto& a, const auto& b) {
    return a->RecordSnapshot().created_unix_seconds() <
           b->RecordSnapshot().created_unix_seconds();
  };
  std::sort(jobs.begin(), jobs.end(), older);
  std::sort(loaded.resumed.begin(), loaded.resumed.end(), older);
  loaded.jobs = static_cast<int>(jobs.size());
  for (std::shared_ptr<Job>& job : jobs) memory_.Add(std::move(job)).IgnoreError();
  for (const std::string& id : lost_ids) Enqueue(id);
  LogEvent("store_loaded", {{"dir", dir_},
                            {"jobs", absl::StrCat(loaded.jobs)},
                            {"resumed", absl::StrCat(loaded.resumed.size())},
                            {"lost", absl::StrCat(lost_ids.size())}});
  return loaded;
}

absl::Status DiskJobStore::Add(std::shared_ptr<Job> job) {
  const std::string id = job->id();
  job->RequireEndRecord();
  // The upload first: a record without its upload could not be run again.
  absl::Status s;
  const std::vector<uint64_t>& part_bytes = job->upload_part_bytes();
  job->ReadUpload([&](absl::string_view upload) {
    v1::UploadHeader header;
    header.set_upload_bytes(upload.size());
    header.set_upload_crc32c(Crc32c(upload));
    for (uint64_t size : part_bytes) header.add_upload_part_bytes(size);
    std::string prefix;
    google::protobuf::io::StringOutputStream output(&prefix);
    if (!google::protobuf::util::SerializeDelimitedToZeroCopyStream(header, &output)) {
      s = absl::InternalError("cannot serialize the upload's header");
      return;
    }
    s = files_->Write(dir_, UploadPathOf(id), {prefix, upload});
  });
  bool ended = false;
  if (s.ok()) s = Write(*job, ended);
  if (!s.ok()) {
    files_->Remove(UploadPathOf(id)).IgnoreError();
    LogEvent("store_write_failed", {{"job", id}, {"message", std::string(s.message())}});
    SetWritable(false);
    return absl::UnavailableError(
        absl::StrCat("the job store ", dir_, " cannot be written: ", s.message()));
  }
  SetWritable(true);
  return memory_.Add(std::move(job));
}

void DiskJobStore::Remove(const std::string& id) {
  memory_.Remove(id);
  files_->Remove(PathOf(id)).IgnoreError();
  files_->Remove(UploadPathOf(id)).IgnoreError();
}

bool DiskJobStore::writable() const {
  absl::MutexLock lock(&mutex_);
  return writable_;
}

std::shared_ptr<Job> DiskJobStore::Find(const std::string& id) const { return memory_.Find(id); }

std::vector<std::shared_ptr<Job>> DiskJobStore::List() const { return memory_.List(); }

int DiskJobStore::RemoveFinishedBefore(absl::Time cutoff) {
  const std::vector<std::shared_ptr<Job>> expired = memory_.TakeFinishedBefore(cutoff);
  for (const std::shared_ptr<Job>& job : expired) {
    files_->Remove(PathOf(job->id())).IgnoreError();
    files_->Remove(UploadPathOf(job->id())).IgnoreError();
  }
  return static_cast<int>(expired.size());
}

void DiskJobStore::Finished(const std::string& id) { Enqueue(id); }

int64_t DiskJobStore::Enqueue(const std::string& id) {
  absl::MutexLock lock(&mutex_);
  if (closed_) return asked_;
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

void DiskJobStore::Close() {
  Flush();
  absl::MutexLock lock(&mutex_);
  closed_ = true;
}

void DiskJobStore::WaitFor(int64_t ticket) {
  // Writes run in the order asked for: once `done_` reaches the ticket, that one is done.
  absl::MutexLock lock(&mutex_);
  const auto written = [this, ticket]() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_) {
    return done_ >= ticket;
  };
  mutex_.Await(absl::Condition(&written));
}

void DiskJobStore::SetWritable(bool writable) {
  {
    absl::MutexLock lock(&mutex_);
    if (writable_ == writable) return;
    writable_ = writable;
    if (writable) {
      // The ends that failed are written again, in the order they failed.
      for (std::string& id : unwritten_) {
        pending_.push_back(std::move(id));
        ++asked_;
      }
      unwritten_.clear();
    }
  }
  LogEvent(writable ? "store_writable" : "store_unwritable", {{"dir", dir_}});
  absl::MutexLock lock(&listener_mutex_);
  // The state now, not `writable`: a change that raced this one is told last.
  bool now = false;
  {
    absl::MutexLock state_lock(&mutex_);
    now = writable_;
  }
  if (listener_) listener_(now);
}

void DiskJobStore::Probe() {
  const std::string check = absl::StrCat(dir_, "/", kWriteCheck);
  const std::string page(4096, '\0');
  if (files_->Write(dir_, check, {page}).ok()) {
    files_->Remove(check).IgnoreError();
    SetWritable(true);
  }
}

void DiskJobStore::WriterLoop() {
  for (;;) {
    std::string id;
    bool probe = false;
    {
      absl::MutexLock lock(&mutex_);
      const auto ready = [this]() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_) {
        return !pending_.empty() || stopping_;
      };
      const auto ready_or_failing = [this]() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_) {
        return !pending_.empty() || stopping_ || !writable_;
      };
      if (writable_) {
        mutex_.Await(absl::Condition(&ready_or_failing));
      } else {
        // While the disk fails, a probe every interval in which nothing is asked for.
        probe = !mutex_.AwaitWithTimeout(absl::Condition(&ready), options_.probe_interval);
      }
      if (!probe) {
        if (pending_.empty()) {
          if (stopping_) return;  // everything written
          continue;               // the disk just failed: wait with probes
        }
        id = std::move(pending_.front());
        pending_.pop_front();
      }
    }
    if (probe) {
      Probe();
      continue;
    }
    WriteRecord(id);
    absl::MutexLock lock(&mutex_);
    ++done_;
  }
}

void DiskJobStore::WriteRecord(const std::string& id) {
  // The job as it is now: a later change enqueues another write, so the last write holds
  // the last state. A job expired meanwhile is not written back.
  const std::shared_ptr<Job> job = memory_.Find(id);
  if (job == nullptr) return;
  bool ended = false;
  if (absl::Status s = Write(*job, ended); !s.ok()) {
    LogEvent("store_write_failed", {{"job", id}, {"message", std::string(s.message())}});
    if (absl::IsResourceExhausted(s)) {
      // Too large to be read back: no disk will take it. Delivered from memory; after a
      // restart the job runs again from its upload.
      job->MarkEndRecorded();
      return;
    }
    if (ended) {
      {
        absl::MutexLock lock(&mutex_);
        unwritten_.push_back(id);
      }
      // Its record still says unfinished and its upload stays: a crash now runs it again, so
      // the end that followers deliver is never undone.
      job->MarkEndRecorded();
    }
    SetWritable(false);
    return;
  }
  SetWritable(true);
  if (ended) {
    files_->Remove(UploadPathOf(id)).IgnoreError();
    job->MarkEndRecorded();
  }
}

absl::Status DiskJobStore::Write(const Job& job, bool& ended) const {
  // The closing events first: a job that ends in between then has a done snapshot and no
  // JobDone, which reads as unfinished until the write its end enqueued replaces it.
  const std::vector<v1::JobEvent> closing = job.ClosingEvents(kChunkBytes);
  const std::vector<v1::JobEvent> events = job.Events();
  const v1::Job snapshot = job.RecordSnapshot();
  ended = !closing.empty();
  std::string bytes;
  {
    google::protobuf::io::StringOutputStream output(&bytes);
    bool ok = google::protobuf::util::SerializeDelimitedToZeroCopyStream(snapshot, &output);
    for (const auto* list : {&events, &closing})
      for (const v1::JobEvent& event : *list)
        ok = ok && google::protobuf::util::SerializeDelimitedToZeroCopyStream(event, &output);
    if (!ok) return absl::InternalError("cannot serialize the job");
  }
  if (static_cast<int64_t>(bytes.size()) > options_.max_record_bytes) {
    return absl::ResourceExhaustedError(absl::StrCat("the record of ", bytes.size(),
                                                     " bytes is over the store's limit of ",
                                                     options_.max_record_bytes));
  }
  return files_->Write(dir_, PathOf(job.id()), {bytes});
}

}  // namespace membrane::server

// DiskJobStore: what a restarted membraned finds of its jobs.
#include "server/disk_job_store.h"

#include <memory>
#include <string>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "absl/synchronization/notification.h"
#include "core/io/file_bytes.h"
#include "tests/server/faulty_store_files.h"
#include "tests/support/scratch_dir.h"

namespace membrane::server {
namespace {

using ::membrane::testing::DiskFaults;
using ::membrane::testing::FaultyStoreFiles;
using ::membrane::testing::ScratchDir;

// The hooks of resumed jobs: their end is written down, as the server's hook does.
DiskJobStore::HookMaker HooksOf(DiskJobStore& store) {
  return [&store](const std::string& id) -> Job::FinishHook {
    return [&store, id](v1::JobState, const absl::Status&, absl::Duration, uint64_t, bool) {
      store.Finished(id);
    };
  };
}

// How many jobs Load found, or -1 with the test failed when it failed.
int LoadCount(DiskJobStore& store) {
  absl::StatusOr<DiskJobStore::Loaded> loaded = store.Load(HooksOf(store));
  EXPECT_TRUE(loaded.ok()) << loaded.status();
  return loaded.ok() ? loaded->jobs : -1;
}

bool Exists(const std::string& path) {
  struct stat info;
  return lstat(path.c_str(), &info) == 0;
}

// A queued job whose end is told to `store`, as the service makes them.
std::shared_ptr<Job> NewJob(DiskJobStore& store, const std::string& id) {
  v1::Parameters parameters;
  parameters.set_surface("cuberille");
  parameters.add_origin(1);
  parameters.add_origin(2);
  parameters.add_origin(3);
  return std::make_shared<Job>(id, "ipv4:10.0.0.7:5555", parameters, std::string(1234, 'u'),
                               UploadMemory::Hold{},
                               [&store, id](v1::JobState, const absl::Status&, absl::Duration,
                                            uint64_t, bool) { store.Finished(id); });
}

void AddProgress(Job& job) {
  v1::JobEvent stage;
  stage.mutable_stage()->set_stage("shrink");
  stage.mutable_stage()->set_phase(v1::StageEvent::STARTED);
  job.AddEvent(stage);
  v1::JobEvent generation;
  generation.mutable_generation()->set_generation(1);
  generation.mutable_generation()->set_plate_size(9);
  job.AddEvent(generation);
}

// Every event a WatchJob of the job would send, serialized, for comparison.
std::vector<std::string> Stream(const Job& job) {
  std::vector<std::string> out;
  for (const v1::JobEvent& e : job.Events()) out.push_back(e.SerializeAsString());
  for (const v1::JobEvent& e : job.ClosingEvents(1 << 20)) out.push_back(e.SerializeAsString());
  return out;
}

TEST(DiskJobStoreTest, FinishedJobsComeBackAsTheyWere) {
  ScratchDir dir;
  const std::string path = dir.File("jobs");
  std::vector<std::string> streams;
  v1::Job before;
  {
    DiskJobStore store(path);
    ASSERT_EQ(LoadCount(store), 0);
    std::shared_ptr<Job> ok = NewJob(store, "r0.00000000000000aa");
    ASSERT_TRUE(store.Add(ok).ok());
    ASSERT_TRUE(ok->Start());
    AddProgress(*ok);
    v1::MeshSummary summary;
    summary.set_faces(12);
    summary.set_closed(true);
    summary.add_genus(0);
    // A mesh over one chunk, so that it is stored in several.
    ok->Succeed("{\"points\": 3}", summary, std::string((1 << 20) + 17, 'm'));
    std::shared_ptr<Job> failed = NewJob(store, "r0.00000000000000bb");
    ASSERT_TRUE(store.Add(failed).ok());
    failed->Fail(absl::InvalidArgumentError("the upload could not be decoded"));
    std::shared_ptr<Job> cancelled = NewJob(store, "r0.00000000000000cc");
    ASSERT_TRUE(store.Add(cancelled).ok());
    cancelled->RequestCancel("cancelled by the client");
    store.Flush();
    before = ok->Snapshot();
    for (const auto& job : {ok, failed, cancelled}) {
      for (const std::string& e : Stream(*job)) streams.push_back(e);
    }
  }
  DiskJobStore store(path);
  ASSERT_EQ(LoadCount(store), 3);
  std::vector<std::string> again;
  for (const char* id : {"r0.00000000000000aa", "r0.00000000000000bb", "r0.00000000000000cc"}) {
    const std::shared_ptr<Job> job = store.Find(id);
    ASSERT_NE(job, nullptr) << id;
    EXPECT_TRUE(job->done());
    for (const std::string& e : Stream(*job)) again.push_back(e);
  }
  EXPECT_TRUE(again == streams) << "the restored jobs do not stream what they streamed";
  const v1::Job after = store.Find("r0.00000000000000aa")->Snapshot();
  EXPECT_EQ(after.SerializeAsString(), before.SerializeAsString());
  EXPECT_EQ(store.Find("r0.00000000000000bb")->Snapshot().error().message(),
            "the upload could not be decoded");
  EXPECT_EQ(store.Find("r0.00000000000000cc")->state(), v1::CANCELLED);
  // Newest first, as before the restart.
  ASSERT_EQ(store.List().size(), 3u);
  EXPECT_EQ(store.List().front()->id(), "r0.00000000000000cc");
}

// The process stopped with a job queued and one running: both run again from their kept
// uploads, under their ids and creation times, from the start (no events).
TEST(DiskJobStoreTest, UnfinishedJobsResumeFromTheirUploads) {
  ScratchDir dir;
  const std::string path = dir.File("jobs");
  v1::Job queued_before;
  {
    DiskJobStore store(path);
    ASSERT_EQ(LoadCount(store), 0);
    std::shared_ptr<Job> queued = NewJob(store, "00000000000000dd");
    queued->set_upload_part_bytes({1000, 234});  // an upload of two Draco parts
    ASSERT_TRUE(store.Add(queued).ok());
    std::shared_ptr<Job> running = NewJob(store, "00000000000000ee");
    ASSERT_TRUE(store.Add(running).ok());
    ASSERT_TRUE(running->Start());
    AddProgress(*running);
    queued_before = queued->Snapshot();
  }
  DiskJobStore store(path);
  absl::StatusOr<DiskJobStore::Loaded> loaded = store.Load(HooksOf(store));
  ASSERT_TRUE(loaded.ok()) << loaded.status();
  EXPECT_EQ(loaded->jobs, 2);
  ASSERT_EQ(loaded->resumed.size(), 2u);
  EXPECT_EQ(loaded->resumed[0]->id(), "00000000000000dd");  // oldest first
  EXPECT_EQ(loaded->resumed[1]->id(), "00000000000000ee");
  EXPECT_THAT(loaded->resumed[0]->upload_part_bytes(), ::testing::ElementsAre(1000, 234));
  EXPECT_TRUE(loaded->resumed[1]->upload_part_bytes().empty());
  for (const std::shared_ptr<Job>& job : loaded->resumed) {
    EXPECT_EQ(job->state(), v1::QUEUED);
    EXPECT_TRUE(job->Events().empty());
    EXPECT_EQ(job->TakeUpload(), std::string(1234, 'u'));
    EXPECT_EQ(store.Find(job->id()), job);
  }
  const v1::Job after = loaded->resumed[0]->Snapshot();
  EXPECT_EQ(after.created_unix_seconds(), queued_before.created_unix_seconds());
  EXPECT_EQ(after.parameters().SerializeAsString(),
            queued_before.parameters().SerializeAsString());
  EXPECT_EQ(after.peer(), queued_before.peer());
  // Once a resumed job's end is written, its upload goes.
  std::shared_ptr<Job> job = loaded->resumed[0];
  ASSERT_TRUE(job->Start());
  job->Succeed("{}", {}, std::string(100, 'm'));
  store.Flush();
  EXPECT_TRUE(job->closed());
  EXPECT_FALSE(Exists(path + "/00000000000000dd.upload"));
  EXPECT_TRUE(Exists(path + "/00000000000000ee.upload"));
}

// An unfinished job whose upload cannot be read comes back FAILED with a status that says
// what to do, written down so that it stays so.
TEST(DiskJobStoreTest, UnfinishedJobWithoutItsUploadComesBackFailedUnavailable) {
  ScratchDir dir;
  const std::string path = dir.File("jobs");
  {
    DiskJobStore store(path);
    ASSERT_EQ(LoadCount(store), 0);
    ASSERT_TRUE(store.Add(NewJob(store, "00000000000000dd")).ok());
    ASSERT_TRUE(store.Add(NewJob(store, "00000000000000de")).ok());
  }
  ASSERT_EQ(unlink((path + "/00000000000000dd.upload").c_str()), 0);
  std::string upload = *ReadFileBytes(path + "/00000000000000de.upload");
  upload.back() ^= 1;  // fails its CRC
  ASSERT_TRUE(WriteFileBytes(path + "/00000000000000de.upload", upload).ok());
  double finished = 0;
  {
    DiskJobStore store(path);
    absl::StatusOr<DiskJobStore::Loaded> loaded = store.Load(HooksOf(store));
    ASSERT_TRUE(loaded.ok());
    EXPECT_EQ(loaded->jobs, 2);
    EXPECT_TRUE(loaded->resumed.empty());
    for (const char* id : {"00000000000000dd", "00000000000000de"}) {
      const v1::Job job = store.Find(id)->Snapshot();
      EXPECT_EQ(job.state(), v1::FAILED) << id;
      EXPECT_EQ(job.error().code(), static_cast<int>(absl::StatusCode::kUnavailable));
      EXPECT_NE(job.error().message().find("submit it again"), std::string::npos)
          << job.error().message();
      EXPECT_GT(job.finished_unix_seconds(), 0);
    }
    EXPECT_NE(store.Find("00000000000000de")->Snapshot().error().message().find("CRC-32C"),
              std::string::npos);
    finished = store.Find("00000000000000dd")->Snapshot().finished_unix_seconds();
    store.Flush();
  }
  DiskJobStore store(path);
  ASSERT_EQ(LoadCount(store), 2);
  EXPECT_EQ(store.Find("00000000000000dd")->Snapshot().finished_unix_seconds(), finished);
  EXPECT_FALSE(Exists(path + "/00000000000000de.upload"));  // its job has ended
}

// An upload without its record is what a crash inside Add leaves (the client never heard of
// the job): removed at the next start.
TEST(DiskJobStoreTest, UploadWithoutARecordIsRemoved) {
  ScratchDir dir;
  const std::string path = dir.File("jobs");
  {
    DiskJobStore store(path);
    ASSERT_EQ(LoadCount(store), 0);
    ASSERT_TRUE(store.Add(NewJob(store, "00000000000000d1")).ok());
  }
  ASSERT_EQ(unlink((path + "/00000000000000d1.job").c_str()), 0);
  DiskJobStore store(path);
  ASSERT_EQ(LoadCount(store), 0);
  EXPECT_FALSE(Exists(path + "/00000000000000d1.upload"));
}

// Records that cannot be trusted are skipped and left for a person to look at; the others load.
TEST(DiskJobStoreTest, UnreadableRecordsAreSkippedAndKept) {
  ScratchDir dir;
  const std::string path = dir.File("jobs");
  {
    DiskJobStore store(path);
    ASSERT_EQ(LoadCount(store), 0);
    std::shared_ptr<Job> job = NewJob(store, "00000000000000a1");
    ASSERT_TRUE(store.Add(job).ok());
    ASSERT_TRUE(job->Start());
    job->Succeed("{}", {}, std::string(5000, 'm'));
    store.Flush();
  }
  const std::string good = *ReadFileBytes(path + "/00000000000000a1.job");
  ASSERT_TRUE(WriteFileBytes(path + "/garbage.job", "\xff\xff\xff\xff not a record").ok());
  ASSERT_TRUE(WriteFileBytes(path + "/00000000000000a2.job", good.substr(0, good.size() - 100))
                  .ok());  // truncated inside the mesh
  std::string corrupt = good;
  corrupt[corrupt.size() - 2000] ^= 1;  // a mesh byte: fails the CRC
  ASSERT_TRUE(WriteFileBytes(path + "/00000000000000a3.job", corrupt).ok());
  ASSERT_TRUE(WriteFileBytes(path + "/00000000000000a4.job", good).ok());  // another id inside
  ASSERT_TRUE(WriteFileBytes(path + "/00000000000000a5.job.tmp", "half a write").ok());
  DiskJobStore store(path);
  ASSERT_EQ(LoadCount(store), 1);
  EXPECT_NE(store.Find("00000000000000a1"), nullptr);
  for (const char* name : {"garbage.job", "00000000000000a2.job", "00000000000000a3.job",
                           "00000000000000a4.job"}) {
    EXPECT_TRUE(ReadFileBytes(path + "/" + name).ok()) << name << " was removed";
  }
  EXPECT_FALSE(ReadFileBytes(path + "/00000000000000a5.job.tmp").ok());
}

TEST(DiskJobStoreTest, ExpiredJobsLeaveTheDirectory) {
  ScratchDir dir;
  const std::string path = dir.File("jobs");
  DiskJobStore store(path);
  ASSERT_EQ(LoadCount(store), 0);
  std::shared_ptr<Job> job = NewJob(store, "00000000000000b1");
  ASSERT_TRUE(store.Add(job).ok());
  job->Fail(absl::InvalidArgumentError("bad"));
  store.Flush();
  ASSERT_TRUE(ReadFileBytes(path + "/00000000000000b1.job").ok());
  EXPECT_EQ(store.RemoveFinishedBefore(absl::Now() + absl::Seconds(1)), 1);
  EXPECT_FALSE(ReadFileBytes(path + "/00000000000000b1.job").ok());
  EXPECT_EQ(store.Find("00000000000000b1"), nullptr);
}

TEST(DiskJobStoreTest, UncreatableDirectoryIsUnavailable) {
  ScratchDir dir;
  ASSERT_TRUE(WriteFileBytes(dir.File("file"), "x").ok());
  DiskJobStore store(dir.File("file") + "/jobs");
  const absl::StatusOr<DiskJobStore::Loaded> loaded = store.Load(HooksOf(store));
  ASSERT_FALSE(loaded.ok());
  EXPECT_EQ(loaded.status().code(), absl::StatusCode::kUnavailable);
  EXPECT_NE(loaded.status().message().find("cannot create the job store"), std::string::npos)
      << loaded.status();
}

// A store that cannot be written would accept no job: a start-up error, not a server that
// answers UNAVAILABLE to everyone.
TEST(DiskJobStoreTest, ReadOnlyDirectoryFailsTheLoad) {
  ScratchDir dir;
  auto faults = std::make_shared<DiskFaults>();
  faults->read_only = true;
  DiskJobStore store(dir.File("jobs"), {}, FaultyStoreFiles(faults));
  const absl::StatusOr<DiskJobStore::Loaded> loaded = store.Load(HooksOf(store));
  ASSERT_FALSE(loaded.ok());
  EXPECT_EQ(loaded.status().code(), absl::StatusCode::kUnavailable);
  EXPECT_NE(loaded.status().message().find("cannot be written"), std::string::npos)
      << loaded.status();
  EXPECT_NE(loaded.status().message().find("Read-only file system"), std::string::npos)
      << loaded.status();
}

// Records are bounded before they are read, and only regular files are read: a huge file, a
// link out of the store and a FIFO are each skipped (and left), the rest loads.
TEST(DiskJobStoreTest, OversizedAndNonRegularRecordsAreSkipped) {
  ScratchDir dir;
  const std::string path = dir.File("jobs");
  DiskJobStoreOptions options;
  options.max_record_bytes = 64 << 10;
  {
    DiskJobStore store(path, options);
    ASSERT_EQ(LoadCount(store), 0);
    std::shared_ptr<Job> job = NewJob(store, "00000000000000c1");
    ASSERT_TRUE(store.Add(job).ok());
    ASSERT_TRUE(job->Start());
    job->Succeed("{}", {}, std::string(5000, 'm'));
    store.Flush();
  }
  const std::string good = *ReadFileBytes(path + "/00000000000000c1.job");
  // Over the limit, however valid: a mesh padded past it would be read whole otherwise.
  ASSERT_TRUE(WriteFileBytes(path + "/00000000000000c2.job", good + std::string(70 << 10, '\0'))
                  .ok());
  ASSERT_TRUE(WriteFileBytes(dir.File("outside.job"), good).ok());
  ASSERT_EQ(symlink(dir.File("outside.job").c_str(), (path + "/00000000000000c1x.job").c_str()),
            0);
  ASSERT_EQ(mkfifo((path + "/00000000000000c3.job").c_str(), 0600), 0);
  DiskJobStore store(path, options);
  ASSERT_EQ(LoadCount(store), 1);
  EXPECT_NE(store.Find("00000000000000c1"), nullptr);
  for (const char* name : {"00000000000000c2.job", "00000000000000c1x.job", "00000000000000c3.job"}) {
    EXPECT_TRUE(Exists(path + "/" + name)) << name << " was removed";
  }
}

// A record bounded by RecordBytesFor the largest mesh holds a mesh of that size with its
// events: the job is written, and read back after a restart with the same mesh.
TEST(DiskJobStoreTest, RecordOfTheLargestResultIsWrittenAndLoaded) {
  ScratchDir dir;
  const std::string path = dir.File("jobs");
  constexpr int64_t kMeshBytes = 3 << 20;  // over a chunk, so that chunks are framed
  DiskJobStoreOptions options;
  options.max_record_bytes = RecordBytesFor(kMeshBytes);
  const std::string mesh(kMeshBytes, 'm');
  {
    DiskJobStore store(path, options);
    ASSERT_EQ(LoadCount(store), 0);
    std::shared_ptr<Job> job = NewJob(store, "00000000000000d1");
    ASSERT_TRUE(store.Add(job).ok());
    ASSERT_TRUE(job->Start());
    job->Succeed("{}", {}, mesh);
    store.Flush();
  }
  const absl::StatusOr<std::string> record = ReadFileBytes(path + "/00000000000000d1.job");
  ASSERT_TRUE(record.ok());
  EXPECT_GT(static_cast<int64_t>(record->size()), kMeshBytes);
  EXPECT_LE(static_cast<int64_t>(record->size()), options.max_record_bytes);
  DiskJobStore store(path, options);
  ASSERT_EQ(LoadCount(store), 1);
  const std::shared_ptr<Job> loaded = store.Find("00000000000000d1");
  ASSERT_NE(loaded, nullptr);
  const std::optional<Job::Outcome> outcome = loaded->Closing();
  ASSERT_TRUE(outcome.has_value());
  EXPECT_TRUE(outcome->mesh.view() == mesh);
}

// Followers deliver a job's end only once its record is on disk: a crash in between cannot
// take back a result a client was given.
TEST(DiskJobStoreTest, AJobClosesOnceItsEndIsWritten) {
  ScratchDir dir;
  auto faults = std::make_shared<DiskFaults>();
  DiskJobStore store(dir.File("jobs"), {}, FaultyStoreFiles(faults));
  ASSERT_EQ(LoadCount(store), 0);
  std::shared_ptr<Job> job = NewJob(store, "00000000000000f1");
  ASSERT_TRUE(store.Add(job).ok());
  {
    absl::MutexLock lock(&faults->mutex);
    faults->hold_records = true;
  }
  ASSERT_TRUE(job->Start());
  job->Succeed("{}", {}, std::string(100, 'm'));
  {
    // The writer is inside the record's write, held.
    absl::MutexLock lock(&faults->mutex);
    faults->mutex.Await(absl::Condition(
        +[](DiskFaults* f) ABSL_EXCLUSIVE_LOCKS_REQUIRED(f->mutex) { return f->held == 1; },
        faults.get()));
  }
  EXPECT_TRUE(job->done());
  EXPECT_FALSE(job->closed());
  // Clients see it running until then; the record has its end.
  EXPECT_EQ(job->Snapshot().state(), v1::RUNNING);
  EXPECT_EQ(job->state(), v1::RUNNING);
  EXPECT_FALSE(job->Closing().has_value());
  EXPECT_EQ(job->RecordSnapshot().state(), v1::SUCCEEDED);
  EXPECT_FALSE(job->ClosingEvents(1 << 20).empty());
  {
    absl::MutexLock lock(&faults->mutex);
    faults->hold_records = false;
  }
  store.Flush();
  EXPECT_TRUE(job->closed());
  EXPECT_EQ(job->Snapshot().state(), v1::SUCCEEDED);
  EXPECT_TRUE(job->Closing().has_value());
  EXPECT_FALSE(Exists(dir.File("jobs") + "/00000000000000f1.upload"));
}

// A disk that cannot be written: Add fails and writes nothing, the store says it is not
// writable (and tells its listener), and recovers by itself once the disk can be written.
TEST(DiskJobStoreTest, UnwritableDiskRefusesJobsUntilItRecovers) {
  ScratchDir dir;
  const std::string path = dir.File("jobs");
  auto faults = std::make_shared<DiskFaults>();
  DiskJobStoreOptions options;
  options.probe_interval = absl::Milliseconds(20);
  DiskJobStore store(path, options, FaultyStoreFiles(faults));
  absl::Mutex mutex;
  std::vector<bool> heard;
  store.SetWritableListener([&](bool writable) {
    absl::MutexLock lock(&mutex);
    heard.push_back(writable);
  });
  ASSERT_EQ(LoadCount(store), 0);
  faults->free_bytes = 1000;  // under the upload, and under the probe's page
  const absl::Status refused = store.Add(NewJob(store, "00000000000000e1"));
  EXPECT_EQ(refused.code(), absl::StatusCode::kUnavailable) << refused;
  EXPECT_NE(refused.message().find("No space left on device"), std::string::npos) << refused;
  EXPECT_EQ(store.Find("00000000000000e1"), nullptr);
  EXPECT_FALSE(Exists(path + "/00000000000000e1.upload"));
  EXPECT_FALSE(Exists(path + "/00000000000000e1.job"));
  EXPECT_FALSE(store.writable());
  faults->free_bytes = -1;
  {
    absl::MutexLock lock(&mutex);
    mutex.Await(absl::Condition(
        +[](std::vector<bool>* h) { return !h->empty() && h->back(); }, &heard));
    EXPECT_EQ(heard, (std::vector<bool>{false, true}));
  }
  EXPECT_TRUE(store.writable());
  EXPECT_TRUE(store.Add(NewJob(store, "00000000000000e2")).ok());
}

// A job's end that cannot be written is delivered anyway, but its upload stays, so that after
// a crash the job runs again rather than coming back unfinished without it; once the disk
// can be written the end is written and the upload removed.
TEST(DiskJobStoreTest, AnEndThatCannotBeWrittenIsWrittenOnceTheDiskRecovers) {
  ScratchDir dir;
  const std::string path = dir.File("jobs");
  auto faults = std::make_shared<DiskFaults>();
  DiskJobStoreOptions options;
  options.probe_interval = absl::Milliseconds(20);
  DiskJobStore store(path, options, FaultyStoreFiles(faults));
  absl::Notification recovered;
  store.SetWritableListener([&](bool writable) {
    if (writable && !recovered.HasBeenNotified()) recovered.Notify();
  });
  ASSERT_EQ(LoadCount(store), 0);
  std::shared_ptr<Job> job = NewJob(store, "00000000000000e3");
  ASSERT_TRUE(store.Add(job).ok());
  faults->read_only = true;
  ASSERT_TRUE(job->Start());
  job->Succeed("{}", {}, std::string(100, 'm'));
  store.Flush();
  EXPECT_TRUE(job->closed());
  EXPECT_FALSE(store.writable());
  EXPECT_TRUE(Exists(path + "/00000000000000e3.upload"));
  faults->read_only = false;
  recovered.WaitForNotification();
  store.Flush();
  EXPECT_FALSE(Exists(path + "/00000000000000e3.upload"));
  DiskJobStore again(path);
  ASSERT_EQ(LoadCount(again), 1);
  EXPECT_EQ(again.Find("00000000000000e3")->state(), v1::SUCCEEDED);
}

}  // namespace
}  // namespace membrane::server

// DiskJobStore: what a restarted membraned finds of its jobs.
#include "server/disk_job_store.h"

#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/io/file_bytes.h"
#include "tests/support/scratch_dir.h"

namespace membrane::server {
namespace {

using ::membrane::testing::ScratchDir;

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
                                            uint64_t) { store.Finished(id); });
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
    ASSERT_EQ(*store.Load(), 0);
    std::shared_ptr<Job> ok = NewJob(store, "r0.00000000000000aa");
    store.Add(ok);
    ASSERT_TRUE(ok->Start());
    AddProgress(*ok);
    v1::MeshSummary summary;
    summary.set_faces(12);
    summary.set_closed(true);
    summary.add_genus(0);
    // A mesh over one chunk, so that it is stored in several.
    ok->Succeed("{\"points\": 3}", summary, std::string((1 << 20) + 17, 'm'));
    std::shared_ptr<Job> failed = NewJob(store, "r0.00000000000000bb");
    store.Add(failed);
    failed->Fail(absl::InvalidArgumentError("the upload could not be decoded"));
    std::shared_ptr<Job> cancelled = NewJob(store, "r0.00000000000000cc");
    store.Add(cancelled);
    cancelled->RequestCancel("cancelled by the client");
    store.Flush();
    before = ok->Snapshot();
    for (const auto& job : {ok, failed, cancelled}) {
      for (const std::string& e : Stream(*job)) streams.push_back(e);
    }
  }
  DiskJobStore store(path);
  ASSERT_EQ(*store.Load(), 3);
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

// The process stopped with a job queued (or running): its upload is gone, so it comes back
// FAILED with a status that says what to do, written down so that it stays so.
TEST(DiskJobStoreTest, InterruptedJobsComeBackFailedUnavailable) {
  ScratchDir dir;
  const std::string path = dir.File("jobs");
  {
    DiskJobStore store(path);
    ASSERT_TRUE(store.Load().ok());
    std::shared_ptr<Job> queued = NewJob(store, "00000000000000dd");
    store.Add(queued);
    std::shared_ptr<Job> running = NewJob(store, "00000000000000ee");
    store.Add(running);
    ASSERT_TRUE(running->Start());
    AddProgress(*running);
    store.Flush();
    // A write of the running job is not asked for until it ends: record its progress too.
    store.Finished("00000000000000ee");
    store.Flush();
  }
  double finished = 0;
  {
    DiskJobStore store(path);
    ASSERT_EQ(*store.Load(), 2);
    for (const char* id : {"00000000000000dd", "00000000000000ee"}) {
      const v1::Job job = store.Find(id)->Snapshot();
      EXPECT_EQ(job.state(), v1::FAILED) << id;
      EXPECT_EQ(job.error().code(), static_cast<int>(absl::StatusCode::kUnavailable));
      EXPECT_NE(job.error().message().find("submit it again"), std::string::npos)
          << job.error().message();
      EXPECT_GT(job.finished_unix_seconds(), 0);
    }
    EXPECT_NE(store.Find("00000000000000ee")->Snapshot().error().message().find("running"),
              std::string::npos);
    EXPECT_EQ(store.Find("00000000000000ee")->Events().size(), 2u);
    finished = store.Find("00000000000000dd")->Snapshot().finished_unix_seconds();
    store.Flush();
  }
  DiskJobStore store(path);
  ASSERT_EQ(*store.Load(), 2);
  EXPECT_EQ(store.Find("00000000000000dd")->Snapshot().finished_unix_seconds(), finished);
}

// Records that cannot be trusted are skipped and left for a person to look at; the others load.
TEST(DiskJobStoreTest, UnreadableRecordsAreSkippedAndKept) {
  ScratchDir dir;
  const std::string path = dir.File("jobs");
  {
    DiskJobStore store(path);
    ASSERT_TRUE(store.Load().ok());
    std::shared_ptr<Job> job = NewJob(store, "00000000000000a1");
    store.Add(job);
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
  ASSERT_EQ(*store.Load(), 1);
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
  ASSERT_TRUE(store.Load().ok());
  std::shared_ptr<Job> job = NewJob(store, "00000000000000b1");
  store.Add(job);
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
  const absl::StatusOr<int> loaded = store.Load();
  ASSERT_FALSE(loaded.ok());
  EXPECT_EQ(loaded.status().code(), absl::StatusCode::kUnavailable);
  EXPECT_NE(loaded.status().message().find("cannot create the job store"), std::string::npos)
      << loaded.status();
}

}  // namespace
}  // namespace membrane::server

// A job's outcome as its followers get it (one shared mesh buffer, however many follow), and
// its end as the server's hook hears it.
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "proto/crc32c.h"
#include "server/job.h"

namespace membrane::server {
namespace {

std::shared_ptr<Job> SucceededJob(std::string mesh) {
  auto job = std::make_shared<Job>("0123456789abcdef", "peer", v1::Parameters(), "upload");
  EXPECT_TRUE(job->Start());
  job->Succeed("{}", v1::MeshSummary(), std::move(mesh));
  return job;
}

TEST(Job, FollowersShareOneMeshBufferInsteadOfCopyingIt) {
  std::string mesh(3 << 20, '\0');
  for (size_t i = 0; i < mesh.size(); ++i) mesh[i] = static_cast<char>(i * 7);
  const std::shared_ptr<Job> job = SucceededJob(mesh);
  const std::optional<Job::Outcome> first = job->Closing();
  const std::optional<Job::Outcome> second = job->Closing();
  ASSERT_TRUE(first.has_value() && second.has_value());
  ASSERT_TRUE(first->result.has_value());
  EXPECT_EQ(first->mesh.view().data(), second->mesh.view().data());  // one buffer, shared
  EXPECT_TRUE(first->mesh.view() == mesh);
  EXPECT_EQ(first->result->result().mesh_bytes(), mesh.size());
  EXPECT_EQ(first->result->result().mesh_crc32c(), Crc32c(mesh));
  EXPECT_EQ(first->done.done().state(), v1::SUCCEEDED);
}

TEST(Job, ClosingEventsChunkTheMeshWholeAndInOrder) {
  const std::string mesh = std::string(2500, 'a') + std::string(10, 'b');
  const std::vector<v1::JobEvent> events = SucceededJob(mesh)->ClosingEvents(1000);
  ASSERT_EQ(events.size(), 1u + 3u + 1u);  // result, 1000 + 1000 + 510 bytes, done
  EXPECT_TRUE(events.front().has_result());
  std::string joined;
  for (size_t i = 1; i + 1 < events.size(); ++i) joined += events[i].mesh_chunk();
  EXPECT_TRUE(joined == mesh);
  EXPECT_EQ(events[3].mesh_chunk().size(), 510u);
  EXPECT_TRUE(events.back().has_done());
}

TEST(Job, RunningJobHasNoOutcomeAndAFailedOneNoMesh) {
  auto job = std::make_shared<Job>("0123456789abcdef", "peer", v1::Parameters(), "upload");
  ASSERT_TRUE(job->Start());
  EXPECT_FALSE(job->Closing().has_value());
  EXPECT_TRUE(job->ClosingEvents(1000).empty());
  job->Fail(absl::InvalidArgumentError("a degenerate cloud"));
  const std::optional<Job::Outcome> outcome = job->Closing();
  ASSERT_TRUE(outcome.has_value());
  EXPECT_FALSE(outcome->result.has_value());
  EXPECT_TRUE(outcome->mesh.empty());
  EXPECT_EQ(outcome->done.done().state(), v1::FAILED);
  EXPECT_EQ(outcome->done.done().status().message(), "a degenerate cloud");
}

// The end hook hears once whether a worker ran the job: a cancel while QUEUED ends it there
// (the server then logs its end, which no worker will), a cancel of a RUNNING one waits for
// the worker's end.
TEST(Job, TheEndHookSaysWhetherTheJobRan) {
  std::vector<std::pair<v1::JobState, bool>> ends;
  const Job::FinishHook hook = [&ends](v1::JobState state, const absl::Status&, absl::Duration,
                                       uint64_t, bool ran) { ends.emplace_back(state, ran); };
  Job queued("0123456789abcdef", "peer", v1::Parameters(), "upload", {}, hook);
  queued.RequestCancel("cancelled by the client");
  EXPECT_FALSE(queued.Start());
  Job running("fedcba9876543210", "peer", v1::Parameters(), "upload", {}, hook);
  ASSERT_TRUE(running.Start());
  running.RequestCancel("cancelled by the client");
  EXPECT_EQ(ends.size(), 1u);  // the running job ends when its worker sees the token
  running.Fail(absl::CancelledError("cancelled while decoding"));
  const std::vector<std::pair<v1::JobState, bool>> expected = {{v1::CANCELLED, false},
                                                                {v1::CANCELLED, true}};
  EXPECT_EQ(ends, expected);
}

}  // namespace
}  // namespace membrane::server

#include "server/job_scheduler.h"

#include <memory>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/synchronization/blocking_counter.h"
#include "absl/synchronization/mutex.h"
#include "gtest/gtest.h"

namespace membrane::server {
namespace {

// Jobs on one worker each find a thread that has run no job before: what a job's thread keeps
// (its cache of freed blocks among them) ends with the job.
TEST(JobScheduler, EachJobRunsOnAThreadOfItsOwn) {
  constexpr int kJobs = 4;
  absl::BlockingCounter ended(kJobs);
  absl::Mutex mutex;
  std::vector<int> jobs_seen_by_their_thread;
  JobScheduler scheduler(1, kJobs, [&](const std::shared_ptr<Job>& job) {
    thread_local int jobs_on_this_thread = 0;
    {
      absl::MutexLock lock(&mutex);
      jobs_seen_by_their_thread.push_back(++jobs_on_this_thread);
    }
    job->Fail(absl::InternalError("a test job"));
    ended.DecrementCount();
  });
  std::vector<std::shared_ptr<Job>> jobs;
  for (int i = 0; i < kJobs; ++i) {
    jobs.push_back(std::make_shared<Job>(absl::StrCat("job-", i), "peer", v1::Parameters(),
                                         std::string()));
    ASSERT_TRUE(scheduler.Submit(jobs.back()).ok());
  }
  ended.Wait();
  absl::MutexLock lock(&mutex);
  EXPECT_EQ(jobs_seen_by_their_thread, std::vector<int>(kJobs, 1));
  for (const auto& job : jobs) EXPECT_TRUE(job->done());
}

}  // namespace
}  // namespace membrane::server

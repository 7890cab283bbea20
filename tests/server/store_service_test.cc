// The service over a disk store whose disk fails (read-only, full): a job is accepted only
// once it is durable; others are refused with a retry delay, health says so, and a metric
// counts them, until the disk can be written again.
#include <memory>
#include <string>

#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include "absl/synchronization/mutex.h"
#include "absl/time/time.h"
#include "google/rpc/error_details.pb.h"
#include "google/rpc/status.pb.h"
#include "tests/server/faulty_store_files.h"
#include "tests/server/http_get.h"
#include "tests/server/service_fixture.h"
#include "tests/support/scratch_dir.h"

namespace membrane::testing {
namespace {

// The retry delay of a status's RetryInfo in ms, or -1 without one.
int64_t RetryDelayMs(const grpc::Status& status) {
  google::rpc::Status details;
  if (!details.ParseFromString(status.error_details()) || details.details_size() != 1) return -1;
  google::rpc::RetryInfo retry;
  if (!details.details(0).UnpackTo(&retry)) return -1;
  return retry.retry_delay().seconds() * 1000 + retry.retry_delay().nanos() / 1000000;
}

class StoreServiceTest : public ServiceTest {
 protected:
  StoreServiceTest() {
    options_.store_dir = dir_.File("jobs");
    options_.metrics_listen = "127.0.0.1:0";
    store_files_ = FaultyStoreFiles(faults_);
  }

  std::string Metrics() { return HttpGet(server_->metrics_port(), "/metrics"); }

  ScratchDir dir_;
  std::shared_ptr<DiskFaults> faults_ = std::make_shared<DiskFaults>();
};

TEST_F(StoreServiceTest, ReadOnlyStoreRefusesJobsUntilItCanBeWritten) {
  StartServer();
  ASSERT_EQ(Health(), "SERVING");
  const std::string cloud = DracoCloud("sphere", 2000);
  faults_->read_only = true;
  // The first job finds out: its upload cannot be written.
  CallResult r = Reconstruct(cloud, {});
  EXPECT_EQ(r.status.error_code(), grpc::StatusCode::UNAVAILABLE) << r.status.error_message();
  EXPECT_NE(r.status.error_message().find("Read-only file system"), std::string::npos)
      << r.status.error_message();
  EXPECT_EQ(RetryDelayMs(r.status), 500);
  EXPECT_TRUE(r.JobId().empty());
  EXPECT_EQ(Health(), "NOT_SERVING");
  // The next is refused before its upload.
  r = Reconstruct(cloud, {});
  EXPECT_EQ(r.status.error_code(), grpc::StatusCode::UNAVAILABLE);
  EXPECT_NE(r.status.error_message().find("cannot be written"), std::string::npos)
      << r.status.error_message();
  EXPECT_EQ(RetryDelayMs(r.status), 500);
  std::string m = Metrics();
  EXPECT_EQ(MetricValue(m, "membrane_store_refused_total"), 2) << m;
  EXPECT_EQ(MetricValue(m, "membrane_reconstruct_refused_total{code=\"UNAVAILABLE\"}"), 2) << m;
  EXPECT_EQ(MetricValue(m, "membrane_store_writable"), 0) << m;
  EXPECT_EQ(MetricValue(m, "membrane_jobs_accepted_total"), 0) << m;

  faults_->read_only = false;
  ASSERT_TRUE(WaitForHealth("SERVING"));
  r = Reconstruct(cloud, {});
  ASSERT_TRUE(r.status.ok()) << r.status.error_message();
  EXPECT_EQ(r.FinalState(), v1::SUCCEEDED);
  m = Metrics();
  EXPECT_EQ(MetricValue(m, "membrane_store_writable"), 1) << m;

  // What a restarted server finds: the job it accepted, nothing of those it refused.
  const std::string accepted = r.JobId();
  server_->Shutdown(absl::ZeroDuration());
  server_.reset();
  StartServer();
  grpc::ClientContext context;
  v1::ListJobsResponse list;
  ASSERT_TRUE(stub_->ListJobs(&context, {}, &list).ok());
  ASSERT_EQ(list.jobs_size(), 1);
  EXPECT_EQ(list.jobs(0).id(), accepted);
  EXPECT_EQ(list.jobs(0).state(), v1::SUCCEEDED);
}

// A full disk takes the small writes and refuses the upload that does not fit: that job is
// refused (not accepted and then lost), and jobs are taken again once there is room.
TEST_F(StoreServiceTest, FullStoreRefusesTheUploadThatDoesNotFit) {
  StartServer();
  const std::string large = DracoCloud("sphere", 30000);
  faults_->free_bytes = 64 << 10;
  ASSERT_GT(large.size(), 64u << 10);
  CallResult r = Reconstruct(large, {});
  EXPECT_EQ(r.status.error_code(), grpc::StatusCode::UNAVAILABLE) << r.status.error_message();
  EXPECT_NE(r.status.error_message().find("No space left on device"), std::string::npos)
      << r.status.error_message();
  EXPECT_EQ(RetryDelayMs(r.status), 500);
  EXPECT_TRUE(r.JobId().empty());
  const std::string m = Metrics();
  EXPECT_EQ(MetricValue(m, "membrane_store_refused_total"), 1) << m;
  faults_->free_bytes = -1;
  // The store's probe (a small write) finds the disk writable again.
  ASSERT_TRUE(WaitForHealth("SERVING"));
  r = Reconstruct(large, {});
  ASSERT_TRUE(r.status.ok()) << r.status.error_message();
  EXPECT_EQ(r.FinalState(), v1::SUCCEEDED);
}

// GetJob and the HTTP API tell a job's end only once its record is on disk: a client told
// SUCCEEDED can fetch the mesh at once, and no crash takes that end back. The record of the
// job's end is held (the one that accepted it goes through) while the job is looked at.
TEST_F(StoreServiceTest, AJobSucceedsForClientsOnceItsEndIsOnDisk) {
  options_.http_listen = "127.0.0.1:0";
  options_.web_dir = MEMBRANE_SOURCE_DIR "/server/web";
  StartServer();
  {
    absl::MutexLock lock(&faults_->mutex);
    faults_->hold_records = true;
    faults_->passing_records = 1;
  }
  const std::string id = StartJobInBackground(DracoCloud("sphere", 2000), {});
  ASSERT_FALSE(id.empty());
  {
    absl::MutexLock lock(&faults_->mutex);
    ASSERT_TRUE(faults_->mutex.AwaitWithTimeout(
        absl::Condition(
            +[](DiskFaults* f) ABSL_EXCLUSIVE_LOCKS_REQUIRED(f->mutex) { return f->held == 1; },
            faults_.get()),
        absl::Seconds(60)));
  }
  // The job has ended; its end is being written.
  {
    grpc::ClientContext context;
    v1::GetJobRequest request;
    request.set_job_id(id);
    v1::Job job;
    ASSERT_TRUE(stub_->GetJob(&context, request, &job).ok());
    EXPECT_EQ(job.state(), v1::RUNNING);
    EXPECT_EQ(job.mesh_bytes(), 0u);
    EXPECT_EQ(job.finished_unix_seconds(), 0);
  }
  const int port = server_->http_port();
  EXPECT_NE(HttpGet(port, "/api/jobs/" + id).find("\"state\":\"RUNNING\""), std::string::npos)
      << HttpGet(port, "/api/jobs/" + id);
  EXPECT_EQ(HttpCall(port, "GET", "/api/jobs/" + id + "/mesh.drc").status, 409);
  {
    absl::MutexLock lock(&faults_->mutex);
    faults_->hold_records = false;
  }
  EXPECT_EQ(Watch(id).FinalState(), v1::SUCCEEDED);
  grpc::ClientContext context;
  v1::GetJobRequest request;
  request.set_job_id(id);
  v1::Job job;
  ASSERT_TRUE(stub_->GetJob(&context, request, &job).ok());
  EXPECT_EQ(job.state(), v1::SUCCEEDED);
  EXPECT_GT(job.mesh_bytes(), 0u);
  const HttpReply mesh = HttpCall(port, "GET", "/api/jobs/" + id + "/mesh.drc");
  EXPECT_EQ(mesh.status, 200);
  EXPECT_EQ(mesh.body.size(), job.mesh_bytes());
}

}  // namespace
}  // namespace membrane::testing

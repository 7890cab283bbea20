// An in-process membrane server on 127.0.0.1:0 and a real gRPC channel to it, with helpers
// to upload clouds (well-formed or not) and collect a job's events.
#ifndef MEMBRANE_TESTS_SERVER_SERVICE_FIXTURE_H_
#define MEMBRANE_TESTS_SERVER_SERVICE_FIXTURE_H_

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include "absl/time/clock.h"
#include "absl/time/time.h"
#include "membrane/v1/reconstruction.grpc.pb.h"
#include "server/clock.h"
#include "server/membrane_server.h"
#include "tests/server/gated_decoder.h"
#include "tests/support/scratch_dir.h"

namespace membrane::testing {

// What one Reconstruct (or WatchJob) call gave.
struct CallResult {
  grpc::Status status;
  std::vector<v1::JobEvent> events;
  // The job id of the Accepted event, or empty.
  std::string JobId() const;
  // The GenerationEvents, in the order they came.
  std::vector<v1::GenerationEvent> Generations() const;
  // The JobDone event's state, or JOB_STATE_UNSPECIFIED when none came.
  v1::JobState FinalState() const;
  // The mesh bytes of the MeshChunks.
  std::string Mesh() const;
};

// How an upload deviates from a well-formed one.
struct UploadTweaks {
  int64_t announced_bytes = -1;  // >= 0: the header's size instead of the real one
  bool wrong_checksum = false;
  std::vector<uint64_t> part_bytes;  // the header's upload_part_bytes
  size_t send_bytes = SIZE_MAX;  // send only this many bytes of the upload
  // Then keep the upload open until the server ends the call, while the server's clock runs
  // (ServiceTest::WhileTimeFlies, a step of stall_step), sending a chunk of `trickle_bytes`
  // (0: an empty one) after each step when `trickle`.
  bool stall = false;
  absl::Duration stall_step = absl::Seconds(10);
  bool trickle = false;
  size_t trickle_bytes = 0;
};

// The server's clock in tests: real time plus an offset that the test moves forward.
class TestClock final : public server::Clock {
 public:
  absl::Time Now() const override {
    return absl::Now() + absl::Nanoseconds(offset_ns_.load(std::memory_order_relaxed));
  }
  void Advance(absl::Duration d) {
    offset_ns_.fetch_add(absl::ToInt64Nanoseconds(d), std::memory_order_relaxed);
  }

 private:
  std::atomic<int64_t> offset_ns_{0};
};

// Polls `done` every 10 ms for up to `seconds`; whether it became true.
bool WaitFor(const std::function<bool()>& done, double seconds);

class ServiceTest : public ::testing::Test {
 protected:
  // Options of a small server: 1 worker, queue of 1, short retry delay, the decoder helper
  // of this build; tests change them before StartServer.
  ServiceTest();
  ~ServiceTest() override;

  // Starts the server with options_ and clock_; fails the test when it cannot listen.
  void StartServer();

  // Runs `call` while clock_ moves forward by `step` every 20 ms of real time, running `tick`
  // (may be empty) after each step: minutes of a stalled client pass in a moment. Returns when
  // `call` does.
  void WhileTimeFlies(absl::Duration step, const std::function<void()>& tick,
                      const std::function<void()>& call);

  // A Draco point cloud of `shape` with `points` points (lossless).
  static std::string DracoCloud(const std::string& shape, int points);

  // One Reconstruct call sending `upload` with `parameters`, reading every event until the
  // call ends or `deadline_seconds` pass.
  CallResult Reconstruct(const std::string& upload, const v1::Parameters& parameters,
                         UploadTweaks tweaks = {}, double deadline_seconds = 60);

  // Starts a Reconstruct call and returns once the job is accepted (its id), leaving the call
  // open in the background (joined at the end of the test).
  std::string StartJobInBackground(const std::string& upload, const v1::Parameters& parameters);

  // WatchJob until the job ends, bounded by `deadline_seconds`.
  CallResult Watch(const std::string& job_id, double deadline_seconds = 60);

  // The health service's answer for `service` ("" = the whole server): SERVING,
  // NOT_SERVING, ... or "ERROR <message>" when the call fails (NOT_FOUND for an unknown name).
  std::string Health(const std::string& service = "");
  // Watches the health service until it answers `status` (true) or `seconds` pass (false).
  bool WaitForHealth(const std::string& status, double seconds = 30);

  // Makes every job's decode wait at a gate until the test opens it (GatedDecoder): call
  // before StartServer. A job held so runs for as long as the test wants, whatever the
  // machine's load; cancel, deadline and queue tests wait on events, not on a slow job.
  void HoldDecodes();
  // With HoldDecodes: starts a job of a small cloud (StartJobInBackground) and returns its id
  // once its decode is held at the gate (empty, and a test failure, when it does not get
  // there). The job keeps the one worker until the gate opens (gate_->Open()) or it ends.
  std::string StartHeldJob();

  // Adds token_, when set, to a call's metadata as its bearer token.
  void Authorize(grpc::ClientContext& context) const;

  server::ServerOptions options_;
  // The bearer token Reconstruct, StartJobInBackground and Watch send (one of
  // options_.clients); empty: none.
  std::string token_;
  TestClock clock_;
  // The disk store's file operations for StartServer (a test's that fail); null: the real ones.
  std::unique_ptr<server::StoreFiles> store_files_;
  // Set by HoldDecodes: the gate's files, and the gate.
  std::unique_ptr<ScratchDir> gate_dir_;
  std::unique_ptr<GatedDecoder> gate_;
  std::unique_ptr<server::MembraneServer> server_;
  std::string address_;
  std::unique_ptr<v1::Reconstruction::Stub> stub_;
  std::vector<std::thread> background_;
  std::vector<std::unique_ptr<grpc::ClientContext>> background_contexts_;
};

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_SERVER_SERVICE_FIXTURE_H_

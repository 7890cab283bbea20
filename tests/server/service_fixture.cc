#include "tests/server/service_fixture.h"

#include <chrono>
#include <thread>

#include "absl/synchronization/notification.h"
#include "absl/time/clock.h"
#include "tests/server/draco_upload.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "proto/crc32c.h"

namespace membrane::testing {

std::string CallResult::JobId() const {
  for (const v1::JobEvent& e : events) {
    if (e.has_accepted()) return e.accepted().job_id();
  }
  return "";
}

std::vector<v1::GenerationEvent> CallResult::Generations() const {
  std::vector<v1::GenerationEvent> out;
  for (const v1::JobEvent& e : events) {
    if (e.has_generation()) out.push_back(e.generation());
  }
  return out;
}

v1::JobState CallResult::FinalState() const {
  for (const v1::JobEvent& e : events) {
    if (e.has_done()) return e.done().state();
  }
  return v1::JOB_STATE_UNSPECIFIED;
}

std::string CallResult::Mesh() const {
  std::string mesh;
  for (const v1::JobEvent& e : events) {
    if (e.has_mesh_chunk()) mesh += e.mesh_chunk();
  }
  return mesh;
}

ServiceTest::ServiceTest() {
  options_.workers = 1;
  options_.queue = 1;
  options_.retry_delay_seconds = 0.5;
  options_.decoder_path = MEMBRANE_DECODE_BINARY;
  options_.decoder_timeout_seconds = 10;
  options_.decoder_memory_bytes = 1LL << 30;
  options_.grace_seconds = 0;
}

ServiceTest::~ServiceTest() {
  if (server_ != nullptr) server_->Shutdown(absl::ZeroDuration());
  for (auto& context : background_contexts_) context->TryCancel();
  for (std::thread& t : background_) t.join();
}

bool WaitFor(const std::function<bool()>& done, double seconds) {
  const absl::Time end = absl::Now() + absl::Seconds(seconds);
  while (!done()) {
    if (absl::Now() > end) return false;
    absl::SleepFor(absl::Milliseconds(10));
  }
  return true;
}

void ServiceTest::StartServer() {
  server_ = std::make_unique<server::MembraneServer>(options_, &clock_, std::move(store_files_));
  absl::StatusOr<int> port = server_->Start("127.0.0.1:0");
  ASSERT_TRUE(port.ok()) << port.status();
  address_ = "127.0.0.1:" + std::to_string(*port);
  stub_ = v1::Reconstruction::NewStub(
      grpc::CreateChannel(address_, grpc::InsecureChannelCredentials()));
}

std::string ServiceTest::DracoCloud(const std::string& shape, int points) {
  return LosslessDracoCloud(shape, points);
}

void ServiceTest::HoldDecodes() {
  gate_dir_ = std::make_unique<ScratchDir>();
  gate_ = std::make_unique<GatedDecoder>(*gate_dir_, MEMBRANE_DECODE_BINARY);
  options_.decoder_path = gate_->path();
  // The decode's wall-clock limit bounds a failure only, never a hold's normal course.
  options_.decoder_timeout_seconds = 600;
}

std::string ServiceTest::StartHeldJob() {
  EXPECT_NE(gate_, nullptr) << "StartHeldJob without HoldDecodes";
  if (gate_ == nullptr) return "";
  const int before = gate_->Decodes();
  const std::string id = StartJobInBackground(DracoCloud("sphere", 2000), {});
  EXPECT_FALSE(id.empty());
  if (id.empty()) return "";
  EXPECT_TRUE(gate_->WaitForDecodes(before + 1)) << "job " << id << " never reached the gate";
  return id;
}

namespace {

// Sends the header and the chunks of `upload` as `tweaks` say; closes the upload unless
// tweaks.stall.
void SendUpload(grpc::ClientReaderWriter<v1::ReconstructRequest, v1::JobEvent>& stream,
                const std::string& upload, const v1::Parameters& parameters,
                const UploadTweaks& tweaks) {
  v1::ReconstructRequest header;
  *header.mutable_header()->mutable_parameters() = parameters;
  header.mutable_header()->set_upload_bytes(
      tweaks.announced_bytes >= 0 ? tweaks.announced_bytes : upload.size());
  header.mutable_header()->set_upload_crc32c(Crc32c(upload) + (tweaks.wrong_checksum ? 1 : 0));
  for (uint64_t size : tweaks.part_bytes) header.mutable_header()->add_upload_part_bytes(size);
  stream.Write(header);
  const std::string sent = upload.substr(0, std::min(tweaks.send_bytes, upload.size()));
  for (size_t at = 0; at < sent.size(); at += 1 << 20) {
    v1::ReconstructRequest chunk;
    chunk.set_chunk(sent.substr(at, 1 << 20));
    if (!stream.Write(chunk)) break;
  }
  if (!tweaks.stall) stream.WritesDone();
}

void SetDeadline(grpc::ClientContext& context, double seconds) {
  context.set_deadline(std::chrono::system_clock::now() +
                       std::chrono::milliseconds(static_cast<int64_t>(seconds * 1000)));
}

}  // namespace

void ServiceTest::Authorize(grpc::ClientContext& context) const {
  if (!token_.empty()) context.AddMetadata("authorization", "Bearer " + token_);
}

CallResult ServiceTest::Reconstruct(const std::string& upload, const v1::Parameters& parameters,
                                    UploadTweaks tweaks, double deadline_seconds) {
  grpc::ClientContext context;
  SetDeadline(context, deadline_seconds);
  Authorize(context);
  auto stream = stub_->Reconstruct(&context);
  SendUpload(*stream, upload, parameters, tweaks);
  CallResult result;
  const auto read_all = [&] {
    v1::JobEvent event;
    while (stream->Read(&event)) result.events.push_back(event);
  };
  if (tweaks.stall) {
    // One writer beside the one reader, as gRPC allows; the writes fail once the call ends.
    const std::string trickle(tweaks.trickle_bytes, 't');
    WhileTimeFlies(
        tweaks.stall_step,
        [&] {
          if (!tweaks.trickle) return;
          v1::ReconstructRequest chunk;
          chunk.set_chunk(trickle);
          stream->Write(chunk);
        },
        read_all);
  } else {
    read_all();
  }
  result.status = stream->Finish();
  return result;
}

void ServiceTest::WhileTimeFlies(absl::Duration step, const std::function<void()>& tick,
                                 const std::function<void()>& call) {
  absl::Notification done;
  std::thread time([&] {
    while (!done.WaitForNotificationWithTimeout(absl::Milliseconds(20))) {
      clock_.Advance(step);
      if (tick) tick();
    }
  });
  call();
  done.Notify();
  time.join();
}

std::string ServiceTest::StartJobInBackground(const std::string& upload,
                                              const v1::Parameters& parameters) {
  auto context = std::make_unique<grpc::ClientContext>();
  SetDeadline(*context, 120);
  Authorize(*context);
  grpc::ClientContext* raw = context.get();
  background_contexts_.push_back(std::move(context));
  auto id = std::make_shared<std::string>();
  auto accepted = std::make_shared<absl::Notification>();
  background_.emplace_back([this, raw, upload, parameters, id, accepted] {
    auto stream = stub_->Reconstruct(raw);
    SendUpload(*stream, upload, parameters, {});
    v1::JobEvent event;
    while (stream->Read(&event)) {
      if (event.has_accepted()) {
        *id = event.accepted().job_id();
        accepted->Notify();
      }
    }
    stream->Finish();
    if (!accepted->HasBeenNotified()) accepted->Notify();
  });
  accepted->WaitForNotificationWithTimeout(absl::Seconds(30));
  return *id;
}

CallResult ServiceTest::Watch(const std::string& job_id, double deadline_seconds) {
  grpc::ClientContext context;
  SetDeadline(context, deadline_seconds);
  Authorize(context);
  v1::WatchJobRequest request;
  request.set_job_id(job_id);
  auto reader = stub_->WatchJob(&context, request);
  CallResult result;
  v1::JobEvent event;
  while (reader->Read(&event)) result.events.push_back(event);
  result.status = reader->Finish();
  return result;
}

std::string ServiceTest::Health(const std::string& service) {
  auto health = grpc::health::v1::Health::NewStub(
      grpc::CreateChannel(address_, grpc::InsecureChannelCredentials()));
  grpc::ClientContext context;
  SetDeadline(context, 5);
  grpc::health::v1::HealthCheckRequest request;
  request.set_service(service);
  grpc::health::v1::HealthCheckResponse response;
  const grpc::Status status = health->Check(&context, request, &response);
  if (!status.ok()) return "ERROR " + status.error_message();
  return grpc::health::v1::HealthCheckResponse::ServingStatus_Name(response.status());
}

bool ServiceTest::WaitForHealth(const std::string& status, double seconds) {
  auto health = grpc::health::v1::Health::NewStub(
      grpc::CreateChannel(address_, grpc::InsecureChannelCredentials()));
  grpc::ClientContext context;
  SetDeadline(context, seconds);
  auto reader = health->Watch(&context, {});
  grpc::health::v1::HealthCheckResponse response;
  // Watch sends the status at once, then each change.
  while (reader->Read(&response)) {
    if (grpc::health::v1::HealthCheckResponse::ServingStatus_Name(response.status()) == status) {
      context.TryCancel();
      reader->Finish();
      return true;
    }
  }
  reader->Finish();
  return false;
}

}  // namespace membrane::testing

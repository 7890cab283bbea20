#include "client/remote_reconstruction.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <string>

#include <grpcpp/client_context.h>
#include <grpcpp/create_channel.h>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/time/clock.h"
#include "client/retry_wait.h"
#include "client/cloud_origin.h"
#include "client/input_files.h"
#include "client/io_errors.h"
#include "client/output_files.h"
#include "client/rpc_errors.h"
#include "client/std_streams.h"
#include "client/upload_plan.h"
#include "client/voxel_keeping_snap.h"
#include "core/io/draco_parts.h"
#include "core/io/mesh_io.h"
#include "core/pipeline/grid_box.h"
#include "core/pipeline/stopwatch.h"
#include "core/pipeline/thread_limits.h"
#include "membrane/v1/reconstruction.grpc.pb.h"
#include "proto/crc32c.h"

namespace membrane::client {
namespace {

constexpr size_t kChunkBytes = 1 << 20;  // well under gRPC's 4 MB message limit
// How long a job's follower keeps trying an unreachable server after its last event.
constexpr absl::Duration kReattachPatience = absl::Seconds(120);
// How long a client waits for a server it never reached (without --timeout, when it submits):
// a wrong address fails within seconds.
constexpr absl::Duration kFirstContactPatience = absl::Seconds(4);
// Jobs the server may lose to restarts (ending UNAVAILABLE) before the client gives up.
constexpr int kMaxSubmissions = 3;

// The cloud as sent: Draco bytes of the positions, and the job's parameters as sent with them
// (params.parameters with the cloud's origin and, unless one was given, its voxel size).
struct Upload {
  std::string bytes;
  std::vector<uint64_t> part_bytes;  // UploadHeader.upload_part_bytes; empty: one part
  v1::Parameters parameters;
  Origin3d origin{0, 0, 0};  // PointCloud::origin, to write the mesh back with
  size_t dropped = 0;        // points left out for NaN or infinite coordinates
  std::optional<std::string> noise_note;  // UploadPlan::noise_note
};

std::chrono::system_clock::time_point ToChrono(absl::Time t) {
  if (t == absl::InfiniteFuture()) return std::chrono::system_clock::time_point::max();
  return absl::ToChronoTime(t);
}

void SetDeadline(grpc::ClientContext& context, absl::Time deadline) {
  if (deadline != absl::InfiniteFuture()) context.set_deadline(ToChrono(deadline));
}

absl::Status DeadlineStatus(const RemoteParams& params) {
  return absl::DeadlineExceededError(
      absl::StrFormat("timed out after %g s", absl::ToDoubleSeconds(params.timeout)));
}

// The server accepted an upload in parts without saying it reads them (Accepted.upload_parts):
// one that predates them would decode the first part alone.
bool PartsUnread(const Upload& upload, const JobEventSink& sink) {
  return sink.accepted() && upload.part_bytes.size() > 1 &&
         sink.upload_parts() != upload.part_bytes.size();
}

// One Reconstruct call: the upload, then the events into `sink`. `reached` tells whether the
// header went out, which needs a connection to the server.
grpc::Status ReconstructOnce(v1::Reconstruction::Stub& stub, const RemoteParams& params,
                             const Upload& upload_cloud, absl::Time deadline,
                             JobEventSink& sink, bool& reached) {
  const std::string& upload = upload_cloud.bytes;
  grpc::ClientContext context;
  SetDeadline(context, deadline);
  Authorize(context, params.server);
  auto stream = stub.Reconstruct(&context);
  v1::ReconstructRequest header;
  *header.mutable_header()->mutable_parameters() = upload_cloud.parameters;
  header.mutable_header()->set_upload_bytes(upload.size());
  header.mutable_header()->set_upload_crc32c(Crc32c(upload));
  for (uint64_t size : upload_cloud.part_bytes) {
    header.mutable_header()->add_upload_part_bytes(size);
  }
  bool sending = stream->Write(header);
  reached = sending;
  for (size_t at = 0; sending && at < upload.size(); at += kChunkBytes) {
    v1::ReconstructRequest chunk;
    chunk.set_chunk(upload.substr(at, kChunkBytes));
    sending = stream->Write(chunk);
  }
  stream->WritesDone();
  v1::JobEvent event;
  while (stream->Read(&event)) {
    sink.Consume(event);
    if (PartsUnread(upload_cloud, sink)) {
      context.TryCancel();  // the caller cancels the job and sends the cloud in one part
      break;
    }
    if (params.drop_after_events > 0 && sink.accepted() &&
        sink.events_in_call() >= params.drop_after_events) {
      context.TryCancel();  // the test hook: as if the connection dropped here
      break;
    }
  }
  return stream->Finish();
}

// The cloud read and encoded for the upload: in Draco parts when `in_parts` and it is large
// enough (DracoPartCount), else as one Draco cloud.
absl::StatusOr<Upload> ReadAndEncode(const RemoteParams& params, RemoteOutcome& outcome,
                                     ProgressPrinter& progress, bool in_parts) {
  const Stopwatch watch;
  progress.Begin(absl::StrCat("decode: reading ", InputName(params.input)));
  // The job does not exist yet: nothing to cancel.
  size_t dropped = 0;
  absl::StatusOr<PointCloud> cloud = ReadInputCloud(params.input, params.input_format,
                                                    CancelToken::Never(), params.invalid_points,
                                                    &dropped);
  if (!cloud.ok()) return FileErrorAsInvalidInput(cloud.status());
  if (absl::Status s = CheckOutputKeepsOrigin(cloud->origin, params.output_format,
                                              OutputName(params.output));
      !s.ok()) {
    return s;
  }
  Upload upload;
  upload.origin = cloud->origin;
  upload.dropped = dropped;
  upload.parameters = params.parameters;
  if (upload.origin != Origin3d{0, 0, 0}) {
    for (double v : upload.origin) upload.parameters.add_origin(v);
  }
  const UploadPlan plan = PlanUpload(*cloud, params.parameters.voxel_size(), MachineThreads());
  if (plan.voxel_size > 0) upload.parameters.set_voxel_size(plan.voxel_size);
  if (plan.voxel_plan) {
    v1::VoxelPlan& sent = *upload.parameters.mutable_voxel_plan();
    sent.set_formula_voxel_size(plan.voxel_plan->formula_voxel_size);
    sent.set_point_noise(plan.voxel_plan->point_noise);
  }
  upload.noise_note = plan.noise_note;
  DracoOptions draco = params.upload;
  if (params.adapt_upload_bits && draco.position_quantization_bits > 0) {
    draco.position_quantization_bits = std::max(draco.position_quantization_bits, plan.bits);
  }
  // Each point stays in its voxel of the planned grid, so that the server's hard voxels are
  // --local's; the cloud is not needed as read after this.
  std::optional<VoxelKeepingSnap> snap;
  if (plan.box) {
    snap = SnapKeepingVoxels(cloud->points, *plan.box, plan.voxel_size,
                             draco.position_quantization_bits, MachineThreads());
    if (snap) draco.box = snap->grid.box;
  }
  // The cloud in parts encoded on this machine's threads and decoded on the job's: Draco codes
  // one cloud on one thread. Parts need a box every part is quantized on, so that they hold
  // the same points as one cloud (draco_parts.h); without the snap's, one part.
  const size_t points = cloud->points.size();
  const int parts =
      in_parts && (draco.position_quantization_bits == 0 || draco.box) ? DracoPartCount(points)
                                                                        : 1;
  absl::StatusOr<DracoParts> encoded =
      EncodeDracoPointCloudParts(std::move(cloud->points), draco, parts, MachineThreads());
  if (!encoded.ok()) {
    return absl::Status(encoded.status().code(),
                        absl::StrCat(InputName(params.input), ": ", encoded.status().message()));
  }
  const double position_error = snap ? snap->max_error : encoded->max_position_error;
  // The server plans its grid on the cloud's box, not on the quantized points' (which can be
  // a plane shorter), when its check of the points against the box will pass.
  if (plan.box && position_error <= plan.voxel_size / kGridBoxStepsPerVoxel) {
    v1::GridBox& box = *upload.parameters.mutable_grid_box();
    box.set_min_x(plan.box->min[0]);
    box.set_min_y(plan.box->min[1]);
    box.set_min_z(plan.box->min[2]);
    box.set_max_x(plan.box->max[0]);
    box.set_max_y(plan.box->max[1]);
    box.set_max_z(plan.box->max[2]);
  }
  outcome.raw_bytes = points * sizeof(Point3f);
  outcome.upload_bytes = encoded->bytes.size();
  const std::string positions =
      draco.position_quantization_bits == 0
          ? std::string("lossless positions")
          : absl::StrFormat("%d-bit positions, each coordinate within %.3g of the file's%s",
                            draco.position_quantization_bits, position_error,
                            snap ? " and in its voxel" : "");
  const std::string dropped_note =
      dropped > 0 ? absl::StrCat(" (", DroppedPointsNote(dropped), ")") : std::string();
  const std::string parts_note =
      encoded->part_bytes.size() > 1 ? absl::StrCat(" in ", encoded->part_bytes.size(), " parts")
                                     : std::string();
  progress.Finish(absl::StrFormat(
      "decode: %d points%s%s, %d bytes as Draco%s (%.1f%% of %d raw float32 bytes; %s) in %.3f s",
      points, OriginNote(cloud->origin), dropped_note, outcome.upload_bytes, parts_note,
      100.0 * outcome.upload_bytes / std::max<uint64_t>(1, outcome.raw_bytes),
      outcome.raw_bytes, positions, watch.Seconds()));
  upload.bytes = std::move(encoded->bytes);
  if (encoded->part_bytes.size() > 1) upload.part_bytes = std::move(encoded->part_bytes);
  return upload;
}

}  // namespace

absl::Status WatchUntilDone(const ServerConnection& server, const std::string& job_id,
                            absl::Time deadline, JobEventSink& sink) {
  std::shared_ptr<grpc::Channel> channel = Connect(server);
  auto stub = v1::Reconstruction::NewStub(channel);
  RetryWait wait(*channel);
  // A server that restarts (a pod rescheduled, a crash) is back within a minute or two: one
  // heard from (this job's events, or its acceptance) is tried that long after its last event.
  // One never heard from (a wrong address) is given up on after kFirstContactPatience.
  bool heard = sink.accepted();
  const absl::Time started = absl::Now();
  absl::Time last_heard = started;
  while (true) {
    grpc::ClientContext context;
    SetDeadline(context, deadline);
    Authorize(context, server);
    RouteToJob(context, job_id);
    v1::WatchJobRequest request;
    request.set_job_id(job_id);
    auto reader = stub->WatchJob(&context, request);
    v1::JobEvent event;
    while (reader->Read(&event)) {
      heard = true;
      last_heard = absl::Now();
      sink.Consume(event);
    }
    const grpc::Status status = reader->Finish();
    if (sink.done()) return sink.Outcome();
    if (status.error_code() == grpc::StatusCode::DEADLINE_EXCEEDED || absl::Now() >= deadline) {
      return absl::DeadlineExceededError(absl::StrCat("timed out following job ", job_id));
    }
    if (status.error_code() != grpc::StatusCode::UNAVAILABLE) {
      return FromGrpcStatus(status, server.address);
    }
    const absl::Time until = std::min(
        deadline, heard ? last_heard + kReattachPatience : started + kFirstContactPatience);
    if (!wait.Wait(status, until)) return FromGrpcStatus(status, server.address);
  }
}

absl::Status WriteReceivedMesh(const std::string& mesh, v1::MeshFormat format,
                               const Origin3d& origin, const std::string& output,
                               FileFormat output_format) {
  const bool ply = format == v1::MESH_FORMAT_PLY;
  const bool as_received = ply ? output_format == FileFormat::kPly
                               : output_format == FileFormat::kDrc && origin == Origin3d{0, 0, 0};
  if (as_received) return WriteOutputBytes(output, mesh);
  absl::StatusOr<TriangleMesh> decoded =
      ply ? ReadMeshFromBuffer(mesh, FileFormat::kPly, "the server's PLY mesh")
          : DecodeDracoMesh(mesh);
  if (!decoded.ok()) {
    return absl::DataLossError(absl::StrCat("the server's mesh: ", decoded.status().message()));
  }
  // A PLY mesh's reader set the origin it moved the positions by, if any.
  if (!ply) decoded->origin = origin;
  return WriteOutputMesh(*decoded, output, output_format);
}

namespace {

// The server's check as the MeshReport fields the summary line and the exit status use.
MeshReport MeshReportOf(const v1::MeshSummary& s) {
  MeshReport m;
  m.vertices = s.vertices();
  m.faces = s.faces();
  m.closed = s.closed();
  m.manifold = s.manifold();
  m.oriented = s.oriented();
  m.shells = s.shells();
  m.genus.assign(s.genus().begin(), s.genus().end());
  return m;
}

}  // namespace

namespace {

// Submits `upload` (retrying a busy or unreachable server) and follows its job to the end,
// re-attaching when the call breaks. OK once `sink` holds the job's end, whatever it is, or
// once the server accepted parts it does not read (PartsUnread: the job is not followed);
// else why the job could not be followed (DeadlineExceeded at `deadline`).
absl::Status SubmitAndFollow(grpc::Channel& channel, v1::Reconstruction::Stub& stub,
                             const RemoteParams& params, const Upload& upload,
                             absl::Time deadline, JobEventSink& sink, ProgressPrinter& progress) {
  RetryWait wait(channel);
  // Busy servers are asked again until the deadline. So are unreachable ones when the user
  // gave a --timeout; without one, a server heard from in this run (a restart) is waited for
  // up to kReattachPatience after it was last heard, and one never heard from (a wrong
  // address) for kFirstContactPatience.
  const bool timeout_given = deadline != absl::InfiniteFuture();
  const absl::Time started = absl::Now();
  absl::Time last_heard = absl::InfinitePast();
  for (int attempt = 1; !sink.accepted(); ++attempt) {
    bool reached = false;
    const grpc::Status status = ReconstructOnce(stub, params, upload, deadline, sink, reached);
    if (sink.accepted() || status.ok()) break;
    if (status.error_code() == grpc::StatusCode::DEADLINE_EXCEEDED) return DeadlineStatus(params);
    if (!IsRetryable(status)) return FromGrpcStatus(status, params.server.address);
    if (reached || !Unreachable(status)) last_heard = absl::Now();
    last_heard = std::max(last_heard, wait.connected_at());
    const bool heard = last_heard != absl::InfinitePast();
    absl::Time until = deadline;
    if (!timeout_given && Unreachable(status)) {
      until = heard ? last_heard + kReattachPatience : started + kFirstContactPatience;
    }
    progress.Finish(absl::StrFormat("server %s (%s); retrying%s",
                                    Unreachable(status) ? "unreachable" : "busy",
                                    status.error_message(),
                                    Unreachable(status) ? " once it is reachable" : ""));
    if (!wait.Wait(status, until)) {
      // The next attempt would come after the deadline: timed out (exit 4), as the user said.
      if (until == deadline && timeout_given) return DeadlineStatus(params);
      // Busy or gone for as long as this client waits: "unavailable" for the exit code (4).
      return absl::UnavailableError(absl::StrFormat(
          "server %s still unavailable or busy after %d attempts (%s); start membraned there, "
          "try later, or use --local",
          params.server.address, attempt, status.error_message()));
    }
  }
  if (PartsUnread(upload, sink)) return absl::OkStatus();
  if (!sink.done()) {
    // The call broke after the job was accepted: the job runs on; follow it by its id.
    progress.Finish(absl::StrCat("connection lost; re-attaching to job ", sink.job_id()));
    absl::Status watched = WatchUntilDone(params.server, sink.job_id(), deadline, sink);
    if (absl::IsDeadlineExceeded(watched)) return DeadlineStatus(params);
    if (!watched.ok() && !sink.done()) return watched;
  }
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<RemoteOutcome> RunRemoteReconstruction(const RemoteParams& params,
                                                      ProgressPrinter& progress) {
  const absl::Time deadline = absl::Now() + params.timeout;
  RemoteOutcome outcome;
  absl::StatusOr<Upload> upload = ReadAndEncode(params, outcome, progress, /*in_parts=*/true);
  if (!upload.ok()) return upload.status();

  std::shared_ptr<grpc::Channel> channel = Connect(params.server);
  auto stub = v1::Reconstruction::NewStub(channel);
  for (int submission = 1;; ++submission) {
    JobEventSink sink(progress);
    sink.set_on_accepted(params.on_accepted);
    if (absl::Status s =
            SubmitAndFollow(*channel, *stub, params, *upload, deadline, sink, progress);
        !s.ok()) {
      return s;
    }
    if (PartsUnread(*upload, sink)) {
      // A server that predates uploads in parts (a replica not yet upgraded) would reconstruct
      // the first part alone: its job is cancelled and the cloud sent again in one part.
      const grpc::Status cancelled =
          CancelRemoteJob(params.server, sink.job_id(), absl::Seconds(5));
      progress.Finish(absl::StrFormat(
          "the server reads no upload in parts (it predates them): job %s %s; sending the "
          "cloud as one Draco cloud",
          sink.job_id(),
          cancelled.ok() ? "cancelled"
                         : absl::StrCat("not cancelled (", cancelled.error_message(), ")")));
      upload = ReadAndEncode(params, outcome, progress, /*in_parts=*/false);
      if (!upload.ok()) return upload.status();
      continue;
    }
    absl::Status ended = sink.Outcome();
    // A job ends UNAVAILABLE only when the server lost it, stopping while it was queued or
    // running (server/README.md, Store): this client still has the cloud, so it sends it again.
    if (absl::IsUnavailable(ended) && submission < kMaxSubmissions && absl::Now() < deadline) {
      progress.Finish(absl::StrCat(ended.message(), "; sending the cloud again"));
      continue;
    }
    if (!ended.ok()) return ended;

    const Stopwatch watch;
    progress.Begin(absl::StrCat("encode: writing ", OutputName(params.output)));
    if (absl::Status s = WriteReceivedMesh(sink.mesh(), v1::MESH_FORMAT_DRACO, upload->origin,
                                           params.output, params.output_format);
        !s.ok()) {
      return s;
    }
    progress.Finish(absl::StrFormat("encode: %s (%d bytes received as Draco) in %.3f s",
                                    OutputName(params.output), sink.mesh().size(),
                                    watch.Seconds()));
    outcome.job_id = sink.job_id();
    outcome.generations = sink.generations();
    outcome.statistics_json = sink.statistics_json();
    if (upload->dropped > 0) outcome.warnings.push_back(DroppedPointsNote(upload->dropped));
    if (upload->noise_note) outcome.warnings.push_back(*upload->noise_note);
    outcome.warnings.insert(outcome.warnings.end(), sink.warnings().begin(),
                            sink.warnings().end());
    outcome.mesh = MeshReportOf(sink.mesh_summary());
    outcome.mesh_bytes = sink.mesh().size();
    return outcome;
  }
}

}  // namespace membrane::client

// `membrane reconstruct --server HOST:PORT`: the cloud read here, sent Draco-compressed to a
// membraned, reconstructed there, and the mesh brought back and written here.
#ifndef MEMBRANE_CLIENT_REMOTE_RECONSTRUCTION_H_
#define MEMBRANE_CLIENT_REMOTE_RECONSTRUCTION_H_

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <grpcpp/channel.h>

#include "absl/status/statusor.h"
#include "absl/time/time.h"
#include "client/job_event_sink.h"
#include "client/progress_printer.h"
#include "client/server_connection.h"
#include "core/engine/membrane_shrinker.h"
#include "core/io/draco_codec.h"
#include "core/io/file_format.h"
#include "core/io/point_cloud_io.h"
#include "core/mesh/mesh_check.h"
#include "membrane/v1/reconstruction.pb.h"

namespace membrane::client {

struct RemoteParams {
  ServerConnection server;     // HOST:PORT, TLS and token
  std::string input;           // point cloud path, or "-" for standard input
  std::string input_format;    // --input-format; empty: by extension (by content for "-")
  // --drop-invalid: points with NaN or infinite coordinates left out before the upload (and
  // counted in a warning) instead of refused.
  InvalidPoints invalid_points = InvalidPoints::kRefuse;
  std::string output;          // mesh path, or "-" for standard output
  FileFormat output_format = FileFormat::kPly;  // of `output` (OutputFormat)
  v1::Parameters parameters;   // sent as they are; the server validates them
  DracoOptions upload;         // compression of the cloud sent (--quantization 0: lossless)
  // --quantization not given: more bits than upload's where the cloud's voxel needs them
  // (PlanUpload).
  bool adapt_upload_bits = false;
  absl::Duration timeout = absl::InfiniteDuration();  // the whole command, retries included
  // Told the job id when the server accepts the job (InterruptWatch::JobAccepted); may be empty.
  std::function<void(const std::string&)> on_accepted;
  // Test hook: cancel the call after this many events of the job, then re-attach with
  // WatchJob as after a dropped connection. 0: never.
  int drop_after_events = 0;
};

struct RemoteOutcome {
  std::string job_id;
  std::vector<GenerationStats> generations;
  std::string statistics_json;  // the server's, as design/contracts.md
  MeshReport mesh;              // the server's check of the mesh (the summary's fields set)
  uint64_t raw_bytes = 0;       // the cloud as float32 x y z
  uint64_t upload_bytes = 0;    // the Draco cloud sent
  uint64_t mesh_bytes = 0;      // the Draco mesh received
  // The points --drop-invalid left out, then the server's (StageEvent.warnings), in order.
  std::vector<std::string> warnings;
};

// Runs the reconstruction on params.server and writes params.output. Without a voxel size in
// params.parameters, the formula-(1) size of the cloud as read is sent (PlanUpload), so the
// server's grid is --local's whatever the upload's quantization merges. Same mesh as --local:
// with params.upload lossless (--quantization 0) the server reconstructs the very points the
// file holds, and the mesh comes back lossless (unless the output is .drc), so the vertices
// and faces equal --local's up to Draco's reordering (tests/server LosslessUpload...). With
// quantized uploads (the default 11 bits) each coordinate moves by at most
// DracoEncoding::max_position_error, and the mesh may differ from --local's by about that.
// Calls refused before the job is accepted are repeated (RetryWait): a busy server
// (RESOURCE_EXHAUSTED with a RetryInfo, or out of call threads; UNAVAILABLE with a RetryInfo
// while it shuts down) after its delay or a backoff, with jitter, until the timeout (for ever
// without one); an unreachable one as soon as it can be connected to again, until the timeout,
// or without one for 2 minutes after it was last reached (a restart) and 4 s when it never was
// (a wrong address). A call that breaks after acceptance is resumed with WatchJob.
// Errors: the reader's status for an unreadable input; the server's status (INVALID_ARGUMENT,
// RESOURCE_EXHAUSTED for its limits, ...) with a "server: " message; Unavailable when the
// server stays unreachable or busy; DeadlineExceeded when the timeout expires; the job's
// status (Cancelled, InvalidArgument, Internal, ...) when it failed; DataLoss for a mesh that
// arrives damaged; InvalidArgument naming the output when it cannot be written, or before the
// upload when the cloud's reader moved it (CoordinateShift) and the output cannot hold its
// origin (.stl, .drc). A moved cloud is sent in its moved positions with its origin in the
// parameters, and the mesh written back at the input's coordinates.
absl::StatusOr<RemoteOutcome> RunRemoteReconstruction(const RemoteParams& params,
                                                      ProgressPrinter& progress);

// Follows job `job_id` with WatchJob into `sink` until it ends, re-attaching after dropped
// calls as RunRemoteReconstruction does, within `deadline`: an unreachable server is tried
// again as soon as it can be connected to, for up to 2 minutes after the job's last event (or
// its acceptance, when `sink` holds it), long enough for a restarted server to come back, and
// for 4 s when it was never heard from; then Unavailable.
absl::Status WatchUntilDone(const ServerConnection& server, const std::string& job_id,
                            absl::Time deadline, JobEventSink& sink);

// Writes a job's `mesh`, encoded as `format` (the job's Parameters.mesh_format), to `output`
// (a file, or "-" for standard output) as `output_format`. A Draco mesh's positions are
// relative to `origin` (the job's Parameters.origin): its bytes go out as they are for Draco
// without an origin, else it is decoded and written with the origin. A PLY mesh holds the
// client's coordinates already: its bytes go out as they are for PLY, else it is read (moved
// near 0 when far from it, as any PLY file) and written. Refused for Draco and STL when the
// mesh has an origin (CheckOriginFitsFormat). DataLoss when the bytes are not a mesh of
// `format`; InvalidArgument naming the output when it cannot be written.
absl::Status WriteReceivedMesh(const std::string& mesh, v1::MeshFormat format,
                               const Origin3d& origin, const std::string& output,
                               FileFormat output_format);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_REMOTE_RECONSTRUCTION_H_

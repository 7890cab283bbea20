// A job's cloud: its Draco upload, decoded in a child process (membrane-decode) as the
// pipeline's decode stage, so that a hostile upload can crash or exhaust only the child.
#ifndef MEMBRANE_SERVER_UPLOAD_SOURCE_H_
#define MEMBRANE_SERVER_UPLOAD_SOURCE_H_

#include <utility>

#include "core/io/decode_subprocess.h"
#include "core/pipeline/cloud_source.h"
#include "server/job.h"

namespace membrane::server {

class UploadSource : public CloudSource {
 public:
  // `job` (not owned) must outlive the source; `origin` is the upload's (Parameters.origin).
  UploadSource(Job& job, DecodeLimits limits, const Origin3d& origin)
      : job_(job), limits_(std::move(limits)), origin_(origin) {}

  // Takes the job's upload, decodes it under `limits` (its parts, if any, on limits.threads) and
  // gives the upload's bytes back to the server's memory for uploads; the cloud gets `origin`.
  // DecodeInSubprocess's errors as they are: InvalidArgument for an upload the decoder rejects or
  // dies on, ResourceExhausted for one over limits.max_points, Cancelled within 50 ms of `cancel`
  // firing, Internal when the decoder cannot be started. The decode counts on `progress`
  // (DecodeProgress).
  absl::StatusOr<PointCloud> Read(const CancelToken& cancel, ProgressRange progress) override;

 private:
  Job& job_;
  const DecodeLimits limits_;
  const Origin3d origin_;
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_UPLOAD_SOURCE_H_

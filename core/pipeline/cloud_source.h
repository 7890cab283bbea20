// Where a reconstruction's point cloud comes from: a file, an upload decoded in a child
// process, a cloud already in memory. The pipeline reads it as its decode stage, timed and
// reported like the others (RunReconstruction, reconstruction_pipeline.h).
#ifndef MEMBRANE_CORE_PIPELINE_CLOUD_SOURCE_H_
#define MEMBRANE_CORE_PIPELINE_CLOUD_SOURCE_H_

#include "absl/status/statusor.h"
#include "core/base/cancel_token.h"
#include "core/base/progress_meter.h"
#include "core/geometry/point_cloud.h"

namespace membrane {

class CloudSource {
 public:
  virtual ~CloudSource() = default;

  // The cloud, with its origin (PointCloud::origin). Called once per run, on the
  // reconstructing thread, before anything else. A non-OK status ends the run as it is: the
  // source names its input in its messages, the pipeline adds nothing. A source that decodes
  // for long polls `cancel` and returns Cancelled soon after it fires (the decoders: within
  // milliseconds). A source that can tell how far it has come counts it on `progress` (the
  // decode stage's meter; a default range counts nowhere); one that does not leaves the
  // stage's fraction unset.
  virtual absl::StatusOr<PointCloud> Read(const CancelToken& cancel, ProgressRange progress) = 0;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_CLOUD_SOURCE_H_

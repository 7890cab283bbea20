#include "server/upload_source.h"

namespace membrane::server {

absl::StatusOr<PointCloud> UploadSource::Read(const CancelToken& cancel, ProgressRange progress) {
  absl::StatusOr<PointCloud> cloud = DecodeInSubprocess(job_.TakeUpload(), limits_, cancel,
                                                         progress, job_.upload_part_bytes());
  job_.ReleaseUploadHold();  // the upload is gone with the decoder's input
  if (!cloud.ok()) return cloud.status();
  cloud->origin = origin_;
  return cloud;
}

}  // namespace membrane::server

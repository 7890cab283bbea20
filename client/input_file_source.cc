#include "client/input_file_source.h"

#include "client/input_files.h"
#include "client/io_errors.h"

namespace membrane::client {

absl::StatusOr<PointCloud> InputFileSource::Read(const CancelToken& cancel,
                                                 ProgressRange progress) {
  absl::StatusOr<PointCloud> cloud =
      ReadInputCloud(path_, format_flag_, cancel, invalid_, &dropped_, progress);
  if (!cloud.ok()) return FileErrorAsInvalidInput(cloud.status());
  return cloud;
}

}  // namespace membrane::client

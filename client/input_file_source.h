// The cloud of `membrane reconstruct --local`: its input file or standard input, read as the
// pipeline's decode stage.
#ifndef MEMBRANE_CLIENT_INPUT_FILE_SOURCE_H_
#define MEMBRANE_CLIENT_INPUT_FILE_SOURCE_H_

#include <cstddef>
#include <string>
#include <utility>

#include "core/io/point_cloud_io.h"
#include "core/pipeline/cloud_source.h"

namespace membrane::client {

class InputFileSource : public CloudSource {
 public:
  // `path`: a point cloud file, or "-" for standard input; `format_flag`: --input-format's
  // value (empty: by the extension, or for "-" by the content); `invalid`: what to do with
  // points that have NaN or infinite coordinates (--drop-invalid).
  InputFileSource(std::string path, std::string format_flag,
                  InvalidPoints invalid = InvalidPoints::kRefuse)
      : path_(std::move(path)), format_flag_(std::move(format_flag)), invalid_(invalid) {}

  // ReadInputCloud (input_files.h: a Draco cloud is decoded in a child process), with the io
  // library's Internal for a file that cannot be read turned into InvalidArgument
  // (FileErrorAsInvalidInput): the messages name the file.
  absl::StatusOr<PointCloud> Read(const CancelToken& cancel, ProgressRange progress) override;

  // The points Read left out for their NaN or infinite coordinates (InvalidPoints::kDrop).
  size_t dropped() const { return dropped_; }

 private:
  std::string path_;
  std::string format_flag_;
  InvalidPoints invalid_;
  size_t dropped_ = 0;
};

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_INPUT_FILE_SOURCE_H_

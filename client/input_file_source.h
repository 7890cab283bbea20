// The cloud of `membrane reconstruct --local`: its input file, read as the pipeline's decode
// stage.
#ifndef MEMBRANE_CLIENT_INPUT_FILE_SOURCE_H_
#define MEMBRANE_CLIENT_INPUT_FILE_SOURCE_H_

#include <string>
#include <utility>

#include "core/pipeline/cloud_source.h"

namespace membrane::client {

class InputFileSource : public CloudSource {
 public:
  // `path`: a point cloud file, its format by extension.
  explicit InputFileSource(std::string path) : path_(std::move(path)) {}

  // ReadInputCloud (input_files.h: a .drc file is decoded in a child process), with the io
  // library's Internal for a file that cannot be read turned into InvalidArgument
  // (FileErrorAsInvalidInput): the messages name the file.
  absl::StatusOr<PointCloud> Read(const CancelToken& cancel) override;

 private:
  std::string path_;
};

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_INPUT_FILE_SOURCE_H_

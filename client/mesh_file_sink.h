// The mesh of `membrane reconstruct --local`: its output file, written as the pipeline's
// encode stage.
#ifndef MEMBRANE_CLIENT_MESH_FILE_SINK_H_
#define MEMBRANE_CLIENT_MESH_FILE_SINK_H_

#include <string>
#include <utility>

#include "core/pipeline/mesh_sink.h"

namespace membrane::client {

class MeshFileSink : public MeshSink {
 public:
  // `path`: the mesh file, its format by extension (.ply .obj .stl .drc);
  // `compression_level`: Draco's, for .drc.
  MeshFileSink(std::string path, int compression_level)
      : path_(std::move(path)), compression_level_(compression_level) {}

  // CheckOutputKeepsOrigin (cloud_origin.h): InvalidArgument "OUTPUT: ..." when a moved
  // cloud's mesh would go to a file of float32 positions (.stl, .drc).
  absl::Status CheckOrigin(const Origin3d& origin) override;

  // WriteMesh, a .drc file on `grid` exactly; a second call writes the file again. A file
  // that cannot be written is InvalidArgument naming it (FileErrorAsInvalidInput).
  absl::Status Write(const TriangleMesh& mesh, const PositionGrid& grid) override;

 private:
  std::string path_;
  int compression_level_;
};

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_MESH_FILE_SINK_H_

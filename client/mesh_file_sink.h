// The mesh of `membrane reconstruct --local`: its output file (or standard output), written as
// the pipeline's encode stage.
#ifndef MEMBRANE_CLIENT_MESH_FILE_SINK_H_
#define MEMBRANE_CLIENT_MESH_FILE_SINK_H_

#include <string>
#include <utility>

#include "core/io/file_format.h"
#include "core/pipeline/mesh_sink.h"

namespace membrane::client {

class MeshFileSink : public MeshSink {
 public:
  // `path`: the mesh file, or "-" for standard output; `format`: its format (.ply .obj .stl
  // .drc: OutputFormat); `compression_level`: Draco's, for .drc.
  MeshFileSink(std::string path, FileFormat format, int compression_level)
      : path_(std::move(path)), format_(format), compression_level_(compression_level) {}

  // CheckOutputKeepsOrigin (cloud_origin.h): InvalidArgument "OUTPUT: ..." when a moved
  // cloud's mesh would go to a format of float32 positions (.stl, .drc).
  absl::Status CheckOrigin(const Origin3d& origin) override;

  // WriteOutputMesh, Draco on `grid` exactly; a second call writes the file again. For
  // standard output the encoding is kept instead, for Flush: a second call replaces it, and
  // nothing reaches the stream before the run is over. Errors as WriteOutputMesh's.
  absl::Status Write(const TriangleMesh& mesh, const PositionGrid& grid) override;

  // Writes the encoding kept for standard output (WriteOutputBytes); OK, doing nothing, for a
  // file or when nothing was kept.
  absl::Status Flush();

 private:
  std::string path_;
  FileFormat format_;
  int compression_level_;
  std::string kept_;  // standard output's encoding, until Flush
};

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_MESH_FILE_SINK_H_

// A finished job's mesh in the format a download asks for, whatever format the job produced
// (Parameters.mesh_format): the HTTP API serves both .drc and .ply of every result.
#ifndef MEMBRANE_SERVER_MESH_DOWNLOAD_H_
#define MEMBRANE_SERVER_MESH_DOWNLOAD_H_

#include <string>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "core/geometry/triangle_mesh.h"
#include "membrane/v1/reconstruction.pb.h"

namespace membrane::server {

// The mesh of a result: `mesh_bytes` as the job with `parameters` encoded them (Draco or PLY),
// in the job's positions (the cloud's, without Parameters.origin). InvalidArgument when the
// bytes do not decode (a result is the server's own: a bug).
absl::StatusOr<TriangleMesh> ResultMesh(absl::string_view mesh_bytes,
                                        const v1::Parameters& parameters);

// `mesh_bytes` (as ResultMesh) in `format`: the bytes themselves when the job produced that
// format; otherwise a Draco job's mesh as binary PLY (at position + origin, in double when the
// job has an origin, as a PLY job would have it), or a PLY job's mesh as lossless Draco (its
// positions without the origin, as a Draco job returns them). ResultMesh's errors.
// The bytes MeshInFormat holds at its peak converting a mesh of `vertices` and `faces` to the
// other format, `mesh_bytes` (the job's, already held) not counted: Draco's decoder or encoder
// and its structures, the mesh, and the converted bytes (tests/bench/bench_download_memory.cc).
int64_t MeshConversionBytes(int64_t vertices, int64_t faces);

absl::StatusOr<std::string> MeshInFormat(absl::string_view mesh_bytes,
                                         const v1::Parameters& parameters, v1::MeshFormat format);

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_MESH_DOWNLOAD_H_

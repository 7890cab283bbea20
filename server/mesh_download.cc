#include "server/mesh_download.h"

#include <utility>

#include "core/io/draco_codec.h"
#include "core/io/mesh_io.h"

namespace membrane::server {
namespace {

bool IsPly(v1::MeshFormat format) { return format == v1::MESH_FORMAT_PLY; }

// MeshConversionBytes's costs, above both directions measured on a 1.53M-face torus mesh
// (767k vertices): Draco to PLY peaked 103 MB over the Draco bytes, PLY to Draco 166 MB over
// the PLY bytes (190 MB here; tests/bench/2026-12-03-download-memory.txt).
constexpr int64_t kConversionBytesPerVertex = 48;
constexpr int64_t kConversionBytesPerFace = 100;

Origin3d OriginOf(const v1::Parameters& parameters) {
  if (parameters.origin_size() != 3) return {0, 0, 0};
  return {parameters.origin(0), parameters.origin(1), parameters.origin(2)};
}

}  // namespace

absl::StatusOr<TriangleMesh> ResultMesh(absl::string_view mesh_bytes,
                                        const v1::Parameters& parameters) {
  if (!IsPly(parameters.mesh_format())) return DecodeDracoMesh(mesh_bytes);
  absl::StatusOr<TriangleMesh> mesh =
      ReadMeshFromBuffer(mesh_bytes, FileFormat::kPly, "the job's PLY mesh");
  if (!mesh.ok()) return mesh.status();
  // The reader moved double positions near 0 by its own origin; the job's positions are
  // relative to the job's origin.
  const Origin3d job = OriginOf(parameters);
  for (Point3f& v : mesh->vertices) {
    for (int a = 0; a < 3; ++a) {
      v[a] = static_cast<float>(static_cast<double>(v[a]) + mesh->origin[a] - job[a]);
    }
  }
  mesh->origin = {0, 0, 0};
  return mesh;
}

int64_t MeshConversionBytes(int64_t vertices, int64_t faces) {
  return kConversionBytesPerVertex * vertices + kConversionBytesPerFace * faces;
}

absl::StatusOr<std::string> MeshInFormat(absl::string_view mesh_bytes,
                                         const v1::Parameters& parameters,
                                         v1::MeshFormat format) {
  if (IsPly(format) == IsPly(parameters.mesh_format())) return std::string(mesh_bytes);
  absl::StatusOr<TriangleMesh> mesh = ResultMesh(mesh_bytes, parameters);
  if (!mesh.ok()) return mesh.status();
  if (IsPly(format)) {
    mesh->origin = OriginOf(parameters);
    return WriteMeshToBuffer(*mesh, FileFormat::kPly);
  }
  DracoOptions lossless;
  lossless.position_quantization_bits = 0;
  absl::StatusOr<DracoEncoding> encoded = EncodeDracoMesh(*mesh, lossless);
  if (!encoded.ok()) return encoded.status();
  return std::move(encoded->bytes);
}

}  // namespace membrane::server

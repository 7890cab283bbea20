#include "core/io/ply_reader.h"

#include <utility>

#include "core/io/ply_body.h"
#include "core/io/ply_header.h"

namespace membrane {

absl::StatusOr<PointCloud> ReadPlyPointCloud(absl::string_view data, absl::string_view source) {
  absl::StatusOr<PlyHeader> header = ParsePlyHeader(data, source);
  if (!header.ok()) return header.status();
  absl::StatusOr<TriangleMesh> body = ReadPlyBody(data, *header, source, /*want_faces=*/false);
  if (!body.ok()) return body.status();
  return PointCloud{std::move(body->vertices), body->origin};
}

absl::StatusOr<TriangleMesh> ReadPlyMesh(absl::string_view data, absl::string_view source) {
  absl::StatusOr<PlyHeader> header = ParsePlyHeader(data, source);
  if (!header.ok()) return header.status();
  return ReadPlyBody(data, *header, source, /*want_faces=*/true);
}

}  // namespace membrane

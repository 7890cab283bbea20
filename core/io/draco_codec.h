// Draco compression of point clouds and triangle meshes, to and from bytes in memory.
//
// Debian's Draco 1.5.5 decoder has known crashes (and unbounded allocations) on crafted
// input. Decoding here is in-process all the same -- it is what this library offers; callers
// that decode untrusted bytes (membraned's uploads, the membrane client's .drc input) run
// these decoders in a child: decode_subprocess.h.
#ifndef MEMBRANE_CORE_IO_DRACO_CODEC_H_
#define MEMBRANE_CORE_IO_DRACO_CODEC_H_

#include <optional>
#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "core/geometry/point_cloud.h"
#include "core/geometry/position_grid.h"
#include "core/geometry/triangle_mesh.h"

namespace membrane {

struct DracoOptions {
  // 0 stores float32 positions exactly (lossless). 1..30 snaps each coordinate to a grid of
  // 2^bits - 1 steps spanning the largest side of the bounding box. 11 is draco_encoder's
  // default.
  int position_quantization_bits = 11;
  // 0 (fastest, largest) .. 10 (slowest, smallest); Draco's encoding and decoding speed is
  // 10 - level. 7 is draco_encoder's default.
  int compression_level = 7;
  // When set (and position_quantization_bits > 0): the quantization box instead of the
  // positions' bounding box, so that positions snapped by PositionGrid{bits, *box}.Snap are
  // stored exactly. Every position must lie inside it.
  std::optional<PositionBox> box = std::nullopt;
};

// The options that store positions snapped to `grid` exactly: its bits and box (no box when
// lossless), at `compression_level`.
inline DracoOptions DracoOptionsOnGrid(const PositionGrid& grid, int compression_level) {
  DracoOptions options;
  options.position_quantization_bits = grid.bits;
  options.compression_level = compression_level;
  if (!grid.lossless()) options.box = grid.box;
  return options;
}

// OK when position_quantization_bits is 0 or in 1..30, compression_level is in 0..10 and the
// box, if any, is finite with a positive range; otherwise InvalidArgument naming the field, its
// value and the valid range.
absl::Status ValidateDracoOptions(const DracoOptions& options);

struct DracoEncoding {
  std::string bytes;
  // A bound, in model units, on |decoded - original| for every coordinate of every position:
  // 0 when lossless; otherwise computed from the quantization grid, not by decoding: half a
  // grid step, range / (2^bits - 1) / 2 with range the largest bounding-box side (or the
  // box's), plus a few float32 rounding units of the coordinates' magnitude (Draco dequantizes
  // in float32). Positions already on the box's grid are stored exactly.
  // The Euclidean error is at most sqrt(3) times this.
  double max_position_error = 0;
};

// DracoEncoding::max_position_error for `positions` encoded with `options`, without encoding
// them: what a caller reports before or beside the encoding. `options` are not validated.
double DracoPositionErrorBound(const std::vector<Point3f>& positions, const DracoOptions& options);

// `cloud` compressed by Draco: its float32 positions, not its origin (the client sends a moved
// cloud's origin beside it). InvalidArgument for invalid options, an empty cloud or
// non-finite coordinates (the quantizer's range would be meaningless); Internal when the
// Draco encoder fails.
absl::StatusOr<DracoEncoding> EncodeDracoPointCloud(const PointCloud& cloud,
                                                    const DracoOptions& options);

// `mesh` compressed by Draco: its float32 positions, not its origin, as for clouds. Draco may
// reorder vertices and faces and, for non-manifold input, duplicate vertices; positions and
// triangles (with their orientation) are kept.
// InvalidArgument for invalid options, a mesh without vertices or faces, non-finite
// coordinates or face indices out of range; Internal when the Draco encoder fails.
absl::StatusOr<DracoEncoding> EncodeDracoMesh(const TriangleMesh& mesh,
                                              const DracoOptions& options);

enum class DracoGeometry { kPointCloud, kMesh };

// What the Draco bytes hold, from their header alone. InvalidArgument when they are not
// Draco data.
absl::StatusOr<DracoGeometry> DracoGeometryOf(absl::string_view bytes);

// Whether DecodeDracoPointCloud accepts a Draco mesh, yielding its vertices.
enum class DracoMeshPolicy { kAcceptMeshVertices, kRejectMesh };

struct DecodedDracoCloud {
  PointCloud cloud;
  // What the bytes held: a mesh's vertices are returned as points under kAcceptMeshVertices.
  DracoGeometry geometry = DracoGeometry::kPointCloud;
  // The bytes' attributes as "TYPE datatype xN" in their order, comma-separated (e.g.
  // "POSITION float32 x3, NORMAL float32 x3"): what the parts of one upload must share
  // (draco_parts.h).
  std::string attributes;
};

// The positions in Draco `bytes`: one point per Draco point for a point cloud, one per
// distinct vertex position for a mesh (faces dropped). InvalidArgument when the bytes are
// not valid Draco data, hold no 3-component numeric position attribute, hold non-finite
// positions, or hold a mesh under kRejectMesh; also when a point cloud's header fails
// CheckDracoPointCloudHeader (draco_header.h: impossible point counts and attribute sizes,
// malformed metadata), checked before Draco allocates anything for them. Draco can still
// blow up on counts inside its coded data: untrusted bytes belong in DecodeInSubprocess
// (decode_subprocess.h). See the file comment on crafted input.
absl::StatusOr<DecodedDracoCloud> DecodeDracoPointCloud(
    absl::string_view bytes, DracoMeshPolicy policy = DracoMeshPolicy::kAcceptMeshVertices);

// The triangle mesh in Draco `bytes`, one vertex per distinct position value (corners that
// differ only in other attributes, such as normals, share a vertex). InvalidArgument when the
// bytes are not a valid Draco mesh (a Draco point cloud included), lack 3-component
// positions, or hold non-finite positions or dangling face indices.
absl::StatusOr<TriangleMesh> DecodeDracoMesh(absl::string_view bytes);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_DRACO_CODEC_H_

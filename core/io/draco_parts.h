// A point cloud as a few Draco point clouds one after the other (an upload's parts), each
// decodable alone, so that the client's encode and the server's decode spread Draco's work
// over threads: Draco encodes and decodes one cloud on one thread (the kd-tree coder is
// serial), 5 s of the 10M-point upload's encode and 3 s of its decode.
// Every part is quantized on one explicit box (or stored lossless), so that a point decodes to
// the same float32 position whichever part holds it: the parts decode to the points of a
// one-part encoding, grouped by part. Draco's kd-tree coder orders the points within a cloud
// either way; the surface's fit sums near points in float32 in their order, so a mesh from
// parts can differ from a one-part upload's in a few vertices by a fraction of a voxel
// (docs/io-decisions.md, "An upload in parts").
#ifndef MEMBRANE_CORE_IO_DRACO_PARTS_H_
#define MEMBRANE_CORE_IO_DRACO_PARTS_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"
#include "core/geometry/point_cloud.h"
#include "core/io/draco_codec.h"

namespace membrane {

// The most parts an upload may have: a bound on the part table a server keeps per job, far
// above what helps (a part per thread of the machines that encode and decode).
inline constexpr int kMaxDracoParts = 64;

// OK when `part_bytes` is empty (one part) or holds at most kMaxDracoParts sizes, each
// positive, that sum to `total_bytes`; otherwise InvalidArgument naming the first part at
// fault (1-based), the count or the sum.
absl::Status CheckDracoPartBytes(absl::Span<const uint64_t> part_bytes, uint64_t total_bytes);

// How many parts a cloud of `points` points is sent as: one per kPointsPerDracoPart points
// (rounded down, at least one), at most kMaxEncodedParts. A cloud under half a million
// points encodes in a few tenths of a second and stays one part (the uploads of older
// clients); 8 parts give both ends' threads slabs to share out, and cost 0.3% more bytes on
// the 10M-point torus (tests/bench/2026-12-05-upload-parts.txt).
inline constexpr size_t kPointsPerDracoPart = size_t{1} << 18;
inline constexpr int kMaxEncodedParts = 8;
int DracoPartCount(size_t points);

struct DracoParts {
  std::string bytes;                 // the parts, one after the other
  std::vector<uint64_t> part_bytes;  // the size of each, in order (one entry for one part)
  double max_position_error = 0;     // DracoEncoding::max_position_error over every part
};

// `points` as up to `parts` Draco point clouds encoded with `options` on `threads` (<= 1: the
// calling thread): the points are dealt into slabs across the longest side of their bounding
// box, of nearly equal counts (one part when they all lie in one slab), and each slab is one
// part. More than one part needs options that put a point on the same position in every part,
// lossless positions or an explicit box; otherwise InvalidArgument. Errors as
// EncodeDracoPointCloud's. `points` is consumed (the slabs are made from it and it is freed).
absl::StatusOr<DracoParts> EncodeDracoPointCloudParts(std::vector<Point3f> points,
                                                      const DracoOptions& options, int parts,
                                                      int threads);

// The points of the Draco data in `bytes`, cut into parts of `part_bytes` (empty: one part,
// which is DecodeDracoPointCloud(bytes, policy)), each decoded by DecodeDracoPointCloud on
// `threads` and the points given part after part. Errors: InvalidArgument when `part_bytes`
// fails CheckDracoPartBytes; a part's DecodeDracoPointCloud error with "part K of N (bytes
// B..E): " before it (the lowest such K); InvalidArgument naming the part when a part's
// geometry (a mesh among point clouds) or attributes differ from part 1's.
absl::StatusOr<DecodedDracoCloud> DecodeDracoPointCloudParts(absl::string_view bytes,
                                                             absl::Span<const uint64_t> part_bytes,
                                                             DracoMeshPolicy policy, int threads);

// The parts that DecodeDracoPointCloudParts joins, each its own DecodedDracoCloud, in order (one
// for empty `part_bytes`), with the same checks and errors: for a writer that passes the points
// on part after part without one array of them all (the decode helper, decode_helper.h).
absl::StatusOr<std::vector<DecodedDracoCloud>> DecodeDracoParts(
    absl::string_view bytes, absl::Span<const uint64_t> part_bytes, DracoMeshPolicy policy,
    int threads);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_DRACO_PARTS_H_

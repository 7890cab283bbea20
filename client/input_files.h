// Reading the clouds and meshes the commands take as input. Draco input is decoded in a child
// process under resource limits, as membraned decodes uploads: fuzzing found Draco files of 30
// to 119 bytes that made Debian's Draco 1.5.5 allocate gigabytes (one: 19 GB and 51 s), one
// of them from a count no header check can see.
#ifndef MEMBRANE_CLIENT_INPUT_FILES_H_
#define MEMBRANE_CLIENT_INPUT_FILES_H_

#include <cstddef>
#include <string>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "core/base/cancel_token.h"
#include "core/base/progress_meter.h"
#include "core/geometry/point_cloud.h"
#include "core/geometry/triangle_mesh.h"
#include "core/io/decode_subprocess.h"
#include "core/io/file_format.h"
#include "core/io/point_cloud_io.h"

namespace membrane::client {

// The first argument that makes `membrane` the decode helper (core/io/decode_helper.h) of
// another `membrane` process; not a subcommand users see.
inline constexpr char kDecodeHelperFlag[] = "--decode-helper";

// The limits of the child that decodes Draco `bytes` for the readers below, named `path` in
// its messages: this executable as its own decode helper, a wall and CPU limit of 30 s plus
// 10 s per MiB of the file, an address space of 1 GiB plus 32 bytes per byte of the file, and
// no point limit (the user's own file; membraned bounds uploads instead).
DecodeLimits DecoderLimits(const std::string& bytes, const std::string& path);

// The points of the cloud at `path`, a file or "-" for standard input, in the format
// `format_flag` names (--input-format; empty: the extension's, or for "-" the one its first
// bytes show, InputFormat), as ReadPointCloudFromBuffer reads them, except that a Draco cloud
// is decoded by this executable run as its own decode helper, in a child under DecoderLimits.
// Where no child can be started (no /proc), it is decoded in this process. Errors as ReadFileBytes',
// ReadInputBytes', InputFormat's and ReadPointCloudFromBuffer's (messages naming the file, or
// "stdin"), and InvalidArgument "PATH could not be decoded: ..." for a child that fails,
// crashes or runs out of its limits; Cancelled when `cancel` fires. Points with a NaN or
// infinite coordinate are refused with InvalidPointsError, or with InvalidPoints::kDrop
// (--drop-invalid) left out and counted in `dropped` (when not null); a Draco cloud's are
// refused either way, by its decoder. `progress` counts a Draco decode (DecodeInSubprocess);
// other formats, read in this process, count nothing.
absl::StatusOr<PointCloud> ReadInputCloud(const std::string& path, absl::string_view format_flag,
                                          const CancelToken& cancel,
                                          InvalidPoints invalid = InvalidPoints::kRefuse,
                                          size_t* dropped = nullptr,
                                          ProgressRange progress = ProgressRange());

// The same for a file already read: `bytes` in `format`, named `path` in messages.
absl::StatusOr<PointCloud> ParseInputCloud(const std::string& bytes, FileFormat format,
                                           const std::string& path, const CancelToken& cancel,
                                           InvalidPoints invalid = InvalidPoints::kRefuse,
                                           size_t* dropped = nullptr,
                                           ProgressRange progress = ProgressRange());

// InvalidArgument "<name>: 12 points have NaN or infinite coordinates (...); --drop-invalid
// leaves them out": the refusal of a cloud whose `count` > 0 points are not finite.
absl::Status InvalidPointsError(absl::string_view name, size_t count);

// "12 points with NaN or infinite coordinates left out by --drop-invalid": the warning of a run
// that dropped `count` points.
std::string DroppedPointsNote(size_t count);

// The mesh at `path` (a file, or "-" for standard input, its format as for ReadInputCloud),
// as ReadMeshFromBuffer reads it, except that a Draco mesh is decoded in a child as above
// (DecodeDracoMesh there). Errors as ReadInputCloud's, ReadMeshFromBuffer's for the parse.
absl::StatusOr<TriangleMesh> ReadInputMesh(const std::string& path, absl::string_view format_flag,
                                           const CancelToken& cancel);

// The same for a file already read.
absl::StatusOr<TriangleMesh> ParseInputMesh(const std::string& bytes, FileFormat format,
                                            const std::string& path, const CancelToken& cancel);

// The name of input `path` in messages: "stdin" for "-", else the path.
std::string InputName(const std::string& path);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_INPUT_FILES_H_

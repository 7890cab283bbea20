// `membrane reconstruct --local`: the shared pipeline in process, with a file in, the
// --memory-limit gate and a file out as its adapters.
#ifndef MEMBRANE_CLIENT_LOCAL_RECONSTRUCTION_H_
#define MEMBRANE_CLIENT_LOCAL_RECONSTRUCTION_H_

#include <cstdint>
#include <string>

#include "absl/status/statusor.h"
#include "client/progress_printer.h"
#include "core/base/cancel_token.h"
#include "core/io/draco_codec.h"
#include "core/io/file_format.h"
#include "core/io/point_cloud_io.h"
#include "core/pipeline/reconstruction_options.h"
#include "core/pipeline/reconstruction_report.h"

namespace membrane::client {

struct ReconstructionParams {
  std::string input;         // point cloud path, or "-" for standard input
  std::string input_format;  // --input-format; empty: by extension (by content for "-")
  // --drop-invalid: points with NaN or infinite coordinates left out (and counted in a
  // warning) instead of refused.
  InvalidPoints invalid_points = InvalidPoints::kRefuse;
  std::string output;        // mesh path, or "-" for standard output
  FileFormat output_format = FileFormat::kPly;  // of `output` (OutputFormat): ply obj stl drc
  ReconstructionOptions options;
  DracoOptions draco;  // used for .drc output only
  // The most memory the run may need by the core's estimates (memory_estimate.h), in bytes;
  // 0: no limit. --memory-limit, by default what the machine has available (MachineMemory).
  int64_t memory_limit_bytes = 0;
};

// Reads params.input, reconstructs its surface (RunReconstruction) and writes it to
// params.output, reporting each stage (and each plate generation) to `progress`. Returns the
// measurements; the output file is written even when the mesh check finds the surface not
// closed or not manifold (the caller decides what that means).
// Errors: the reader's status (InvalidArgument / NotFound, message naming the
// file) for unreadable input; InvalidArgument naming the file for a degenerate cloud (no
// points, all equal, coplanar); ResourceExhausted naming --voxel-size for a grid over a given
// --voxel-budget (naming the budget) or over the machine's memory, and for a grid or a surface
// over params.memory_limit_bytes (checked before the grid is allocated and again once the
// membrane is known, when a noisy cloud's foam of a membrane shows), naming the bytes and
// --memory-limit; Cancelled when
// `cancel` fires; InvalidArgument naming the output path when it cannot be written. Standard
// output ("-") gets the mesh once the run is over, and nothing before.
absl::StatusOr<ReconstructionReport> RunLocalReconstruction(const ReconstructionParams& params,
                                                            const CancelToken& cancel,
                                                            ProgressPrinter& progress);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_LOCAL_RECONSTRUCTION_H_

// The stages of `membrane reconstruct --local`, in process: decode, voxelize, shrink, relax,
// surface, check, encode. Free of command-line parsing, so a server can run the same code.
#ifndef MEMBRANE_CLIENT_RECONSTRUCTION_PIPELINE_H_
#define MEMBRANE_CLIENT_RECONSTRUCTION_PIPELINE_H_

#include <string>

#include "absl/status/statusor.h"
#include "client/progress_printer.h"
#include "client/reconstruction_report.h"
#include "client/surface_builder.h"
#include "core/engine/cancel_token.h"
#include "core/engine/membrane_shrinker.h"
#include "core/engine/voxelization.h"
#include "core/io/draco_codec.h"

namespace membrane::client {

struct ReconstructionParams {
  std::string input;   // point cloud path; format by extension
  std::string output;  // mesh path; format by extension (.ply .obj .stl .drc)
  VoxelizeOptions voxelize;
  ShrinkOptions shrink;
  bool relax = true;
  SurfaceKind surface = SurfaceKind::kSmooth;
  DracoOptions draco;  // used for .drc output only
};

// Reads params.input, reconstructs its surface and writes it to params.output, reporting each
// stage (and each plate generation) to `progress`. Returns the measurements; the output file
// is written even when the mesh check finds the surface not closed or not manifold (the
// caller decides what that means).
// Errors: the reader's status (InvalidArgument / NotFound / Unimplemented, message naming the
// file) for unreadable input; InvalidArgument naming the file for a degenerate cloud (no
// points, all equal, coplanar); ResourceExhausted for a grid over the voxel budget, naming
// --voxel-size and --voxel-budget; Cancelled when `cancel` fires (polled within the shrink,
// the relaxation and the smooth surface, and between stages); InvalidArgument naming the
// output path when it cannot be written.
absl::StatusOr<ReconstructionReport> RunReconstruction(const ReconstructionParams& params,
                                                       const CancelToken& cancel,
                                                       ProgressPrinter& progress);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_RECONSTRUCTION_PIPELINE_H_

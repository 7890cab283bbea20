// Validation of a job's Parameters on arrival, before any work is queued.
#ifndef MEMBRANE_SERVER_PARAMETER_CHECKS_H_
#define MEMBRANE_SERVER_PARAMETER_CHECKS_H_

#include <cstdint>

#include "absl/status/statusor.h"
#include "core/io/draco_codec.h"
#include "core/pipeline/reconstruction_pipeline.h"
#include "membrane/v1/reconstruction.pb.h"

namespace membrane::server {

struct JobSettings {
  ReconstructionOptions reconstruction;
  DracoOptions mesh_encoding;  // of the result mesh, when it is Draco
  bool ply_mesh = false;       // the result mesh as binary PLY (Parameters.mesh_format)
  Origin3d origin{0, 0, 0};    // the upload's origin (Parameters.origin), for the statistics
};

// The settings `parameters` ask for, defaults filled in, the voxel budget capped at
// `server_voxel_budget` (0: no cap; the job's own budget, 0 or up to 1e12, holds alone).
// InvalidArgument naming the field and its allowed range for the
// first value out of range, e.g. "initial_plate 200000 is out of range [0, 100000]", or for an
// origin of other than 0 or 3 finite values of magnitude up to 2^40, or for a grid_box that
// is not finite or whose min is not below its max on some axis (CheckGridBox). A schedule or
// surface named wrongly is quoted as ClientText (bounded and escaped).
absl::StatusOr<JobSettings> CheckParameters(const v1::Parameters& parameters,
                                            int64_t server_voxel_budget);

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_PARAMETER_CHECKS_H_

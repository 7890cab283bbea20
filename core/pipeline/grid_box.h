// The box a reconstruction plans its grid on when the caller gives one (ReconstructionOptions::
// grid_box) instead of the points' own: a client that uploads a quantized copy of its cloud
// sends the box of the cloud as read, so that the server's grid (origin and dimensions) is the
// one `membrane reconstruct --local` plans on that cloud. Quantization moves the extreme points
// by up to half a step, and a box one voxel face away from a side of the data region then
// loses or gains a plane (docs/pipeline-decisions.md, "The grid of an upload is planned on the
// client's box, and its points keep their voxels").
#ifndef MEMBRANE_CORE_PIPELINE_GRID_BOX_H_
#define MEMBRANE_CORE_PIPELINE_GRID_BOX_H_

#include "absl/status/status.h"
#include "core/geometry/point_cloud.h"

namespace membrane {

// The points may lie outside a given box by at most voxel_size / kGridBoxStepsPerVoxel on any
// side: the largest step of an upload planned by client/upload_plan.h, the most its
// voxel-keeping snap moves a coordinate (client/voxel_keeping_snap.h).
inline constexpr int kGridBoxStepsPerVoxel = 8;

// OK when every coordinate of `box` is finite and min < max on each axis; otherwise
// InvalidArgument naming grid_box, the axis and the values ("grid_box z: min 2 is not below
// max 1", "grid_box x: max inf is not finite").
absl::Status CheckGridBox(const Box3d& box);

// OK when `points` (CheckedBounds of the points) lies within `box` grown by
// voxel_size / kGridBoxStepsPerVoxel on every side; otherwise InvalidArgument naming grid_box,
// the first axis and side out of reach, by how far, and the allowance ("grid_box does not
// contain the points: their y max 1.25 is 0.2 above the box's 1.05, more than the 0.00625
// (1/8 of the voxel size 0.05) allowed for the upload's quantization").
absl::Status CheckGridBoxHoldsPoints(const Box3d& box, const Box3d& points, double voxel_size);

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_GRID_BOX_H_

// The upload's positions moved onto Draco's grid without leaving their voxels: a coordinate
// that Draco's rounding would carry across a face of the grid the client planned goes to the
// grid node on its own side instead. The server, planning on the same box and voxel
// (Parameters.grid_box, voxel_size), then finds every point in the voxel --local finds it in:
// the same hard voxels, where plain rounding moved points within half a step of a face into
// the next voxel (the 10M-point scan-like bunny: 56 hard voxels more, and genus [2] instead of
// --local's [0]).
#ifndef MEMBRANE_CLIENT_VOXEL_KEEPING_SNAP_H_
#define MEMBRANE_CLIENT_VOXEL_KEEPING_SNAP_H_

#include <cstdint>
#include <optional>
#include <vector>

#include "core/geometry/point_cloud.h"
#include "core/geometry/position_grid.h"

namespace membrane::client {

struct VoxelKeepingSnap {
  PositionGrid grid;            // the Draco grid the positions lie on (its bits and box)
  int64_t moved_coordinates = 0;  // coordinates put on the node beside the nearest one
  double max_error = 0;          // the largest |snapped - original| coordinate, model units
};

// Moves each of `points` onto the Draco grid of `bits` over `box` (GridOverBox: the box's
// values survive Draco's option text, so a decoder returns exactly these positions): to the
// nearest node, or, where that node lies in another voxel along an axis (DataVoxelAlong of
// `box`, `voxel_size`), to the next node back towards the point, inside its voxel. Each
// coordinate then moves by at most one step. nullopt, and `points` unchanged, when the step is
// over voxel_size / kGridBoxStepsPerVoxel (a voxel holds too few nodes, and the server's check
// of the points against the box would refuse them) or `bits` is 0. The points are moved on
// `threads`, with the same result for any number.
std::optional<VoxelKeepingSnap> SnapKeepingVoxels(std::vector<Point3f>& points, const Box3d& box,
                                                  double voxel_size, int bits, int threads = 1);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_VOXEL_KEEPING_SNAP_H_

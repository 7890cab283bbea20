// A cloud whose quantized copy has a grid one plane shorter or longer than its own: the case of
// the box a client sends with its upload (core/pipeline/grid_box.h), for the pipeline, service
// and end-to-end tests alike.
#ifndef MEMBRANE_TESTS_SUPPORT_PLANE_EDGE_CLOUD_H_
#define MEMBRANE_TESTS_SUPPORT_PLANE_EDGE_CLOUD_H_

#include <array>

#include "core/geometry/point_cloud.h"

namespace membrane::testing {

struct PlaneEdgeCloud {
  PointCloud cloud;         // points of a unit sphere
  int bits = 11;            // Draco position bits of the quantized copy
  PointCloud quantized;     // the cloud through Draco at `bits`, decoded
  Box3d box;                // CheckedBounds of `cloud`
  Box3d quantized_box;      // CheckedBounds of `quantized`
  double voxel_size = 0;    // a whole number of voxels falls between the two boxes on `axis`
  int axis = 0;
  // DataDims of each box: Voxelize's data region.
  std::array<int, 3> data_dims{};
  std::array<int, 3> quantized_data_dims{};
};

// `points` sphere points (synth seed 1), their copy at `bits`, and the voxel size, near
// 1/24 of the sphere's side, at which the copy's box is a plane shorter or longer than the
// cloud's on the axis where Draco moved the extreme point most; the Draco step is then at most
// 1/8 of that voxel (client/upload_plan.h plans `bits` for it). Fails the test when no axis
// moved.
PlaneEdgeCloud MakePlaneEdgeCloud(int points, int bits = 11);

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_SUPPORT_PLANE_EDGE_CLOUD_H_

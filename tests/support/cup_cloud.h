// A thin-walled open cup (issue 18): a cylinder of radius 1 and height 1.2 whose inside is
// hollowed from the top, leaving a side wall and a bottom of the same thickness. Topologically
// a ball (1 shell, genus 0) however thin the wall; its inside must stay open.
#ifndef MEMBRANE_TESTS_SUPPORT_CUP_CLOUD_H_
#define MEMBRANE_TESTS_SUPPORT_CUP_CLOUD_H_

#include <cstdint>

#include "core/geometry/point_cloud.h"

namespace membrane::testing {

inline constexpr double kCupRadius = 1.0;
inline constexpr double kCupHeight = 1.2;

// The formula-(1) voxel (EstimateVoxelSize) of a cup cloud of `points` points: its box is the
// cylinder's, whatever the wall.
double CupVoxelSize(int64_t points);

// `points` points uniform on the cup's whole surface (outer side, inner side, outer bottom,
// inner bottom, rim, each by its area), the wall and bottom `wall_voxels` times
// CupVoxelSize(points) thick; fixed seed `seed`. Exact positions, no noise.
PointCloud CupCloud(double wall_voxels, int64_t points, uint64_t seed = 1);

// The volume of the cup's solid (side wall and bottom) and of the whole cylinder, for a wall
// `wall` model units thick.
double CupSolidVolume(double wall);
double CupCylinderVolume();

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_SUPPORT_CUP_CLOUD_H_

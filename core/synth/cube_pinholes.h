// The `cube-pinholes` shape: a cube shell exactly one voxel thick, built for one voxel size,
// with two small holes on opposite walls, lined up along x.
//
// To get the intended voxels, voxelize with voxel size exactly grid.voxel_size and the grid
// origin at the cloud's bounding-box minimum (core/engine Voxelize does both when given that
// voxel size). Why that works:
//   - voxel (0, 0, 0) holds a point exactly at its corner, grid.origin (a float value), and
//     every other point lies in [0.25 l, 0.75 l] of its voxel on each axis, so the bounding-box
//     min is exactly grid.origin;
//   - the far corner voxel holds its centre, so each bounding-box side L lies in
//     [(m - 0.5) l, (m - 0.25) l], and both floor(L / l) + 1 and ceil(L / l) give m voxels;
//   - floor((p - min) / l) is the intended voxel for every point: each is >= 0.25 l from
//     its voxel's faces, far above float rounding at l >= 0.001.
// Every wall voxel except the 2 k^2 hole voxels holds at least one point, so it is hard.
// Formula (1) estimates about l / sqrt(points per voxel) for this cloud (about l / 2 with the
// automatic size), so pass grid.voxel_size explicitly.
#ifndef MEMBRANE_CORE_SYNTH_CUBE_PINHOLES_H_
#define MEMBRANE_CORE_SYNTH_CUBE_PINHOLES_H_

#include <array>
#include <cstdint>

#include "absl/status/statusor.h"
#include "core/geometry/point_cloud.h"
#include "core/synth/synth_options.h"

namespace membrane {

// Points per wall voxel aimed at when SynthOptions::voxel_size is 0.
inline constexpr int kCubePointsPerVoxel = 4;

// The voxels of a cube-pinholes cloud. Voxel (i, j, k), each in [0, side), covers
// origin + [i, i + 1) * voxel_size (likewise j, k) in model units.
struct CubePinholesGrid {
  double voxel_size = 0.0;               // l, model units
  int side = 0;                          // m: the cube is m x m x m voxels, m >= 3
  std::array<double, 3> origin{};        // corner of voxel (0, 0, 0) = the cloud's bbox min
  int hole_size = 1;                     // k
  int hole_lo = 1;                       // the holes are voxels (0, j, k) and (m - 1, j, k)
                                         // for j, k in [hole_lo, hole_lo + hole_size)
  int64_t open_wall_voxels = 0;          // wall voxels minus the 2 k^2 hole voxels

  // True for the cube's wall: some coordinate is 0 or side - 1. `c` must be in [0, side)^3.
  bool IsWall(const std::array<int, 3>& c) const;
  // True for the 2 k^2 hole voxels (on the walls x = 0 and x = side - 1).
  bool IsHole(const std::array<int, 3>& c) const;
  // True for a voxel holding points: a wall voxel that is not a hole.
  bool IsHard(const std::array<int, 3>& c) const { return IsWall(c) && !IsHole(c); }
};

// The grid of SynthesizeShape(options) for cube-pinholes. With options.voxel_size = l > 0 the
// cube has m = max(3, round(2 / l)) voxels per side (about 2 units across); with 0, m is the
// largest side with at least kCubePointsPerVoxel points per open wall voxel and l = 2 / m.
// The cube is centred on the origin. InvalidArgument, naming the field and its range, when the
// options are invalid, when hole_size > m - 2 (a hole must not touch the wall's edges), or
// when points < open_wall_voxels (every open wall voxel needs a point).
absl::StatusOr<CubePinholesGrid> CubePinholesGridFor(const SynthOptions& options);

// The cube-pinholes cloud: exactly options.points points, each open wall voxel holding its
// centre (voxel (0,0,0): its corner) plus points uniform within +-0.25 l of the centre, the
// points spread as evenly as possible (counts differ by at most one; the voxels getting one
// more are drawn from the seed). InvalidArgument as CubePinholesGridFor, and when holes,
// noise or density_ratio are not 0, 0 and 1 (they would break the voxel mapping).
absl::StatusOr<PointCloud> SynthesizeCubePinholes(const SynthOptions& options);

}  // namespace membrane

#endif  // MEMBRANE_CORE_SYNTH_CUBE_PINHOLES_H_

// Synthetic benchmark clouds sized for a target grid at the formula-(1) voxel size.
//
// Formula (1) gives l = sqrt(2 S / N), S = lx ly + ly lz + lz lx the bounding box's half
// surface, and Voxelize gives floor(L_d / l) + 1 + 2 kPadding voxels on axis d. For a cube of
// side L (the sphere, the two spheres) the grid side is about L / l = sqrt(N / 6): N = 6 D^2
// points give a D^3 data grid, whatever L (D = 100, 200, 400: 60k, 240k, 960k points).
#ifndef MEMBRANE_TESTS_BENCH_BENCH_CLOUDS_H_
#define MEMBRANE_TESTS_BENCH_BENCH_CLOUDS_H_

#include <cstdint>
#include <string>

#include "absl/status/statusor.h"
#include "core/geometry/point_cloud.h"

namespace membrane::bench {

// Points that make formula (1) give `target_side` voxels (padding included) along `axis` of
// the box `bounds`: l = L_axis / (target_side - 2 kPadding - 0.5), N = ceil(2 S / l^2).
int64_t PointsForGridSide(const Box3d& bounds, int axis, int target_side);

// A cloud of the catalogue shape `shape` (SynthesizeShape, uniform density, seed 1) whose
// formula-(1) grid is about target_side^3 voxels, padding included (for the sphere-like
// shapes: the bounds are measured on a probe cloud and refined once).
absl::StatusOr<PointCloud> SynthForGridSide(const std::string& shape, int target_side);

// Every k-th point of `cloud`, evenly spread over its order (point i is kept when
// floor((i + 1) m / N) > floor(i m / N), m of N points kept), with m the point count that makes
// formula (1) give `target_side` voxels (padding included) along `axis` of the cloud's box:
// the same object on a coarser grid at the paper's own voxel size. InvalidArgument for a
// degenerate cloud or when the cloud has too few points for that side.
absl::StatusOr<PointCloud> SubsampleForGridSide(const PointCloud& cloud, int axis,
                                                int target_side);

// The tall shape standing in for the paper's Buddha (309 x 745 x 309): `count` unit spheres
// stacked along y, centres `spacing` apart (1.43 for three spheres: bounding box 2 x 4.86 x 2,
// the Buddha grid's 1 : 2.41 : 1), sampled uniformly on the surface of their union (each
// sphere's SynthesizeShape("sphere") cloud, seed 1 + i, without the points inside another
// sphere). About `points` points; one shell, genus 0.
absl::StatusOr<PointCloud> StackedSpheres(int64_t points, int count = 3, double spacing = 1.43);

// StackedSpheres with the point count that makes formula (1) give `target_height` voxels
// (padding included) along y; 745 gives about 309 x 745 x 309 with about 1.09 M points.
absl::StatusOr<PointCloud> StackedSpheresForHeight(int target_height, int count = 3,
                                                   double spacing = 1.43);

}  // namespace membrane::bench

#endif  // MEMBRANE_TESTS_BENCH_BENCH_CLOUDS_H_

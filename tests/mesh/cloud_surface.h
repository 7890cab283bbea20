// The smooth surface of a test cloud as the pipeline builds it, for the tests that measure the
// surface over a shape they generate (hole caps).
#ifndef MEMBRANE_TESTS_MESH_CLOUD_SURFACE_H_
#define MEMBRANE_TESTS_MESH_CLOUD_SURFACE_H_

#include <cstdint>
#include <functional>

#include "absl/status/statusor.h"
#include "core/geometry/point_cloud.h"
#include "core/geometry/triangle_mesh.h"
#include "core/geometry/vec3.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/smooth_surface.h"

namespace membrane::testing {

// `n` points uniformly on the unit sphere (directions of Gaussian triples drawn with `seed`),
// but none within `hole` of the pole (0, 0, 1): a scan with one data hole.
PointCloud SphereWithHole(int n, double hole, uint64_t seed);

struct CloudSurface {
  TriangleMesh mesh;
  SmoothSurfaceStats stats;
  double voxel_size = 0;  // the grid's
};

// Shrinks `cloud` at the formula-(1) voxel size (or exactly `voxel_size` when it is > 0),
// relaxes the membrane and builds SmoothSurface with `options` from the cloud's points.
// Fails with the first stage's status.
absl::StatusOr<CloudSurface> SmoothSurfaceOfCloud(const PointCloud& cloud,
                                                  const SmoothSurfaceOptions& options,
                                                  double voxel_size = 0);

// What the cap tests measure of one surface: over the vertices `in_hole` picks, the largest and
// the mean of `error` (model units) in voxels, the caps' statistics and the mesh's check.
struct CapMeasure {
  double max_error = 0;
  double mean_error = 0;
  int vertices = 0;
  HoleCapStats caps;
  MeshReport check;
};

// SmoothSurfaceOfCloud(cloud, options, voxel_size), measured. A failed stage fails the calling
// test (EXPECT) and gives an empty measure.
CapMeasure MeasureCap(const PointCloud& cloud, const SmoothSurfaceOptions& options,
                      double voxel_size, const std::function<bool(const Vec3d&)>& in_hole,
                      const std::function<double(const Vec3d&)>& error);

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_MESH_CLOUD_SURFACE_H_

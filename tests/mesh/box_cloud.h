// Points on the faces of a box, for the tests that build a surface over a box-shaped solid
// with parts of its faces unscanned (hole caps).
#ifndef MEMBRANE_TESTS_MESH_BOX_CLOUD_H_
#define MEMBRANE_TESTS_MESH_BOX_CLOUD_H_

#include <functional>
#include <random>

#include "absl/status/statusor.h"
#include "core/geometry/point_cloud.h"
#include "core/geometry/triangle_mesh.h"
#include "core/geometry/vec3.h"

namespace membrane::testing {

// Points uniform on the faces of the box [lo, hi], `per_unit_area` per unit of area, drawn face
// by face (y = hi, y = lo, x = hi, x = lo, z = hi, z = lo) from `rng`; those `keep` refuses are
// drawn but left out, so the others do not depend on it.
PointCloud BoxFacePoints(const Vec3d& lo, const Vec3d& hi, int per_unit_area,
                         std::mt19937_64& rng, const std::function<bool(const Vec3d&)>& keep);

// A slab [-2, 2] x [-0.5, 0] x [-2, 2] with a box [-1, 1] x [0, 1.5] x [-1, 1] standing on it;
// their inner edge between the box's face x = 1 and the slab's top runs along z through
// kSlabCorner.
inline const Vec3d kSlabCorner{1, 0, 0};

// A prism over that edge: its slope from (1 + size, 0) to (1, size) across x and y, for
// |z| <= length (how a membrane whose plates could not enter the corner leaves it).
struct Shelf {
  double size = 0;
  double length = 0;
};

// Points on the surface of the box on the slab, `per_unit_area` per unit of area, `keep`
// deciding which stay; with a shelf, on the surface of their union with it. The same seed
// every call: the same points for the same arguments.
PointCloud BoxOnSlab(int per_unit_area, const Shelf* shelf,
                     const std::function<bool(const Vec3d&)>& keep);

// A hole over the inner edge under a shelf: the surface nets (no fit, no caps) of the box on
// the slab with `shelf` over its edge, at `voxel_size`, and the cloud of the box on the slab
// without the points within `hole_radius` of kSlabCorner. Fails as SmoothSurfaceOfCloud.
struct ShelvedHole {
  TriangleMesh nets;
  PointCloud holed;
};
absl::StatusOr<ShelvedHole> ShelvedHoleOverTheEdge(const Shelf& shelf, double hole_radius,
                                                   double voxel_size);

// Distance from p to the solid's surface near the inner edge: the slab's top (x >= 1, y = 0)
// and the box's face (x = 1, y >= 0), across the edge.
double SlabCornerDistance(const Vec3d& p);

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_MESH_BOX_CLOUD_H_

// Points on the faces of a box, for the tests that build a surface over a box-shaped solid
// with parts of its faces unscanned (hole caps).
#ifndef MEMBRANE_TESTS_MESH_BOX_CLOUD_H_
#define MEMBRANE_TESTS_MESH_BOX_CLOUD_H_

#include <functional>
#include <random>

#include "core/geometry/point_cloud.h"
#include "core/geometry/vec3.h"

namespace membrane::testing {

// Points uniform on the faces of the box [lo, hi], `per_unit_area` per unit of area, drawn face
// by face (y = hi, y = lo, x = hi, x = lo, z = hi, z = lo) from `rng`; those `keep` refuses are
// drawn but left out, so the others do not depend on it.
PointCloud BoxFacePoints(const Vec3d& lo, const Vec3d& hi, int per_unit_area,
                         std::mt19937_64& rng, const std::function<bool(const Vec3d&)>& keep);

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_MESH_BOX_CLOUD_H_

// Point clouds as the core sees them: positions only, in model units.
#ifndef MEMBRANE_CORE_GEOMETRY_POINT_CLOUD_H_
#define MEMBRANE_CORE_GEOMETRY_POINT_CLOUD_H_

#include <array>
#include <vector>

namespace membrane {

// A position in model units. float32 is what scanners and Draco deliver.
using Point3f = std::array<float, 3>;

// Where a geometry's position (0, 0, 0) lies in the coordinates of the file it came from or
// goes to: the readers move clouds given in coordinates too large for float32 (georeferenced
// scans: UTM eastings of 500,000 m, ECEF) near the origin (see core/io/coordinate_shift.h),
// and the writers that can hold doubles add it back. Zero for everything else.
using Origin3d = std::array<double, 3>;

// A point cloud: positions only; normals and colours are not used by the method.
struct PointCloud {
  std::vector<Point3f> points;
  Origin3d origin{0, 0, 0};  // file coordinates = position + origin
};

// Axis-aligned bounding box in model units (double: sums of many floats).
struct Box3d {
  std::array<double, 3> min{0, 0, 0};
  std::array<double, 3> max{0, 0, 0};
  // Side lengths max - min.
  std::array<double, 3> Extent() const {
    return {max[0] - min[0], max[1] - min[1], max[2] - min[2]};
  }
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_GEOMETRY_POINT_CLOUD_H_

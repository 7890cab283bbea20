// Writing plain-text point lists (.xyz).
#ifndef MEMBRANE_CORE_IO_XYZ_WRITER_H_
#define MEMBRANE_CORE_IO_XYZ_WRITER_H_

#include <string>

#include "core/geometry/point_cloud.h"

namespace membrane {

// One "x y z" line per point, numbers in the shortest form that reads back exactly, no
// header or count line. Never fails.
std::string EncodeXyzPointCloud(const PointCloud& cloud);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_XYZ_WRITER_H_

// Formatting numbers for the text writers (OBJ, XYZ) so that reading them back is exact.
#ifndef MEMBRANE_CORE_IO_ASCII_FORMAT_H_
#define MEMBRANE_CORE_IO_ASCII_FORMAT_H_

#include <string>

#include "core/geometry/point_cloud.h"

namespace membrane {

// Appends the shortest decimal text that reads back as exactly `value` ("0.1", "1e+30").
void AppendShortestFloat(float value, std::string* out);

// Appends "<x> <y> <z>" with AppendShortestFloat.
void AppendPointText(const Point3f& point, std::string* out);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_ASCII_FORMAT_H_

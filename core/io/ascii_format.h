// Formatting numbers for the text writers (OBJ, XYZ) so that reading them back is exact.
#ifndef MEMBRANE_CORE_IO_ASCII_FORMAT_H_
#define MEMBRANE_CORE_IO_ASCII_FORMAT_H_

#include <string>

#include "core/geometry/point_cloud.h"

namespace membrane {

// Appends the shortest decimal text that reads back as exactly `value` ("0.1", "1e+30").
void AppendShortestFloat(float value, std::string* out);

// Appends "<x> <y> <z>" of point + origin: with AppendShortestFloat on the axes where the
// origin is 0, and elsewhere as the shortest text that reads back as exactly the double sum
// ("500000.12345678912").
void AppendPointText(const Point3f& point, const Origin3d& origin, std::string* out);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_ASCII_FORMAT_H_

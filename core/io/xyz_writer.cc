#include "core/io/xyz_writer.h"

#include "core/io/ascii_format.h"

namespace membrane {

std::string EncodeXyzPointCloud(const PointCloud& cloud) {
  std::string out;
  for (const Point3f& p : cloud.points) {
    AppendPointText(p, cloud.origin, &out);
    out.push_back('\n');
  }
  return out;
}

}  // namespace membrane

#include "core/io/ascii_format.h"

#include <array>
#include <charconv>

namespace membrane {

void AppendShortestFloat(float value, std::string* out) {
  // 32 bytes hold any float in the shortest form ("-1.1754944e-38" is 14).
  std::array<char, 32> buffer;
  const std::to_chars_result result =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  out->append(buffer.data(), result.ptr);
}

namespace {

void AppendShortestDouble(double value, std::string* out) {
  // 32 bytes hold any double in the shortest form ("-2.2250738585072014e-308" is 24).
  std::array<char, 32> buffer;
  const std::to_chars_result result =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  out->append(buffer.data(), result.ptr);
}

}  // namespace

void AppendPointText(const Point3f& point, const Origin3d& origin, std::string* out) {
  for (int k = 0; k < 3; ++k) {
    if (k > 0) out->push_back(' ');
    if (origin[k] == 0) {
      AppendShortestFloat(point[k], out);
    } else {
      AppendShortestDouble(static_cast<double>(point[k]) + origin[k], out);
    }
  }
}

}  // namespace membrane

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

void AppendPointText(const Point3f& point, std::string* out) {
  AppendShortestFloat(point[0], out);
  out->push_back(' ');
  AppendShortestFloat(point[1], out);
  out->push_back(' ');
  AppendShortestFloat(point[2], out);
}

}  // namespace membrane

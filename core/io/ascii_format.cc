#include "core/io/ascii_format.h"

#include <array>
#include <charconv>

namespace membrane {

namespace {

// The shortest text that reads back as exactly `value`, float or double. 32 bytes hold any of
// them ("-2.2250738585072014e-308" is 24).
template <typename T>
void AppendShortest(T value, std::string* out) {
  std::array<char, 32> buffer;
  const std::to_chars_result result =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  out->append(buffer.data(), result.ptr);
}

}  // namespace

void AppendShortestFloat(float value, std::string* out) { AppendShortest(value, out); }

void AppendPointText(const Point3f& point, const Origin3d& origin, std::string* out) {
  for (int k = 0; k < 3; ++k) {
    if (k > 0) out->push_back(' ');
    if (origin[k] == 0) {
      AppendShortestFloat(point[k], out);
    } else {
      AppendShortest(static_cast<double>(point[k]) + origin[k], out);
    }
  }
}

}  // namespace membrane

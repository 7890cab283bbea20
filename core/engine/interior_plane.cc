#include "core/engine/interior_plane.h"

namespace membrane {

FlatBitset InteriorPlane(const std::array<int, 3>& d) {
  // Rows of ones from x = 1 to nx - 2, set a word at a time.
  FlatBitset plane(static_cast<int64_t>(d[0]) * d[1] * d[2]);
  for (int z = 1; z + 1 < d[2]; ++z)
    for (int y = 1; y + 1 < d[1]; ++y) {
      int64_t i = d[0] * (y + static_cast<int64_t>(d[1]) * z) + 1;
      const int64_t end = i + d[0] - 2;
      uint64_t* w = plane.words();
      while (i < end && (i & 63) != 0) plane.set(i++);
      for (; i + 64 <= end; i += 64) w[i >> 6] = ~0ull;
      while (i < end) plane.set(i++);
    }
  return plane;
}

}  // namespace membrane

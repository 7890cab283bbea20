#include "tests/support/uniform_noise.h"

#include <cstddef>

namespace membrane::testing {

PointCloud UniformNoise(int points, uint32_t seed) {
  uint32_t state = seed;
  auto next = [&state] {
    state = state * 1664525u + 1013904223u;  // Numerical Recipes' LCG: 24 high bits used
    return static_cast<float>(state >> 8) / static_cast<float>(1 << 24);
  };
  PointCloud cloud;
  cloud.points.reserve(static_cast<size_t>(points));
  for (int i = 0; i < points; ++i) {
    const float x = next(), y = next(), z = next();
    cloud.points.push_back({x, y, z});
  }
  return cloud;
}

}  // namespace membrane::testing

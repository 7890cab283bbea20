// Points with no surface to find: uniform in the unit cube, from a fixed generator so that
// every run and every machine gets the same cloud (std's distributions may differ).
#ifndef MEMBRANE_TESTS_SUPPORT_UNIFORM_NOISE_H_
#define MEMBRANE_TESTS_SUPPORT_UNIFORM_NOISE_H_

#include <cstdint>

#include "core/geometry/point_cloud.h"

namespace membrane::testing {

// `points` points uniform in [0, 1)^3, the same for the same `seed`.
PointCloud UniformNoise(int points, uint32_t seed);

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_SUPPORT_UNIFORM_NOISE_H_

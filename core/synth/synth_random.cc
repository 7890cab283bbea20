#include "core/synth/synth_random.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace membrane {

std::mt19937_64 SeededStream(uint64_t seed, uint32_t stream) {
  std::seed_seq seq{static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32), stream};
  return std::mt19937_64(seq);
}

double Uniform01(std::mt19937_64& rng) {
  // The top 53 bits fill a double's mantissa exactly: no rounding up to 1.
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

double StandardNormal(std::mt19937_64& rng) {
  // 1 - U lies in (0, 1], so the logarithm is finite.
  const double u1 = 1.0 - Uniform01(rng);
  const double u2 = Uniform01(rng);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

Vec3d RandomUnitVector(std::mt19937_64& rng) {
  // Archimedes: z is uniform on [-1, 1] for a uniform point on the sphere.
  const double z = 2.0 * Uniform01(rng) - 1.0;
  const double phi = 2.0 * std::numbers::pi * Uniform01(rng);
  const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {s * std::cos(phi), s * std::sin(phi), z};
}

}  // namespace membrane

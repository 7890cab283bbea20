// exp(-x) for the Gaussian weights of the point fitting (point_fitting.h): inline, with a short
// dependency chain, where the library call was a tenth of the fit (5 million calls per cloud).
#ifndef MEMBRANE_CORE_MESH_FAST_EXP_H_
#define MEMBRANE_CORE_MESH_FAST_EXP_H_

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

namespace membrane {
namespace fast_exp_internal {

// 2^(-j/64), j = 0..63.
inline const std::array<double, 64> kTable = [] {
  std::array<double, 64> t{};
  for (int j = 0; j < 64; ++j) t[j] = std::exp2(-j / 64.0);
  return t;
}();

}  // namespace fast_exp_internal

// exp(-x) for 0 <= x <= 700, within 1e-15 relative of the exact value (a weight, not a
// result: the fit's targets then differ from std::exp's by far less than float32 rounding).
// Outside that range the result is unspecified (x is clamped to it).
inline double ExpNeg(double x) {
  x = x < 0 ? 0 : (x > 700 ? 700 : x);
  // exp(-x) = 2^-(k/64) * exp(-r), k = round(64 x / ln 2), |r| <= ln(2) / 128; ln(2) / 64 in
  // two parts so that r is exact to the last bits. The series of exp(-r) to r^5 is then
  // within 4e-17, and short: a long Horner chain was latency-bound.
  constexpr double k64Log2e = 92.33248261689366, kLn2Hi = 0.010830424696223417,
                   kLn2Lo = 2.572804622327669e-14;
  const int64_t k = static_cast<int64_t>(x * k64Log2e + 0.5);
  const double kd = static_cast<double>(k);
  const double r = (x - kd * kLn2Hi) - kd * kLn2Lo;
  const double r2 = r * r;
  const double p = (1 - r) + r2 * ((0.5 - r * (1.0 / 6)) + r2 * (1.0 / 24 - r * (1.0 / 120)));
  const uint64_t scale = static_cast<uint64_t>(1023 - (k >> 6)) << 52;
  return p * fast_exp_internal::kTable[k & 63] * std::bit_cast<double>(scale);
}

// exp(-x) in float for 0 <= x <= 87, within 3e-7 relative of the exact value; x is clamped
// to that range. No table and no branch: a loop over an array of these compiles to SIMD
// instructions (the fit's weights, gaussian_plane_sums.h, four or eight at a time).
inline float ExpNegF(float x) {
  x = x < 0.0f ? 0.0f : x;
  x = x > 87.0f ? 87.0f : x;
  // exp(-x) = 2^-k * exp(r), k = round(x / ln 2), r = k ln 2 - x in [-0.35, 0.35]; ln 2 in two
  // parts (the first with few mantissa bits, so k * kLn2Hi is exact) keeps r exact to float
  // rounding also for large x. exp(r) by its Taylor series to r^6 (error below 1.3e-7).
  constexpr float kLog2e = 1.44269504f, kLn2Hi = 0.693145751953125f, kLn2Lo = 1.42860677e-06f;
  constexpr float kRound = 12582912.0f;  // 1.5 * 2^23: adding it rounds to an integer
  const float k = (x * kLog2e + kRound) - kRound;
  const float r = (k * kLn2Hi - x) + k * kLn2Lo;
  constexpr float c2 = 1.0f / 2, c3 = 1.0f / 6, c4 = 1.0f / 24, c5 = 1.0f / 120, c6 = 1.0f / 720;
  const float p = 1.0f + r * (1.0f + r * (c2 + r * (c3 + r * (c4 + r * (c5 + r * c6)))));
  const int32_t biased = (127 - static_cast<int32_t>(k)) << 23;  // 2^-k, k <= 126
  return p * std::bit_cast<float>(biased);
}

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_FAST_EXP_H_

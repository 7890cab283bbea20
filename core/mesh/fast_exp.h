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

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_FAST_EXP_H_

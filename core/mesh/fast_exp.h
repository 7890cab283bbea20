// exp(-x) four floats at a time, for the Gaussian weights of the point fitting
// (near_point_sums.h, point_fitting.h): no table and no branch, so it compiles to SIMD
// instructions; a library call per weight would be a tenth of the fit (5 million weights per
// cloud).
#ifndef MEMBRANE_CORE_MESH_FAST_EXP_H_
#define MEMBRANE_CORE_MESH_FAST_EXP_H_

#include <bit>
#include <cstdint>

namespace membrane {

// Four floats (GCC/Clang vector extension; on targets without SIMD registers the compiler
// lowers it to scalar code) and four int32 of the same size.
using V4f = float __attribute__((vector_size(16)));
using V4i = int32_t __attribute__((vector_size(16)));

inline V4f SplatV4f(float f) { return V4f{f, f, f, f}; }

// exp(-x) in each lane for 0 <= x <= 87, within 3e-7 relative of the exact value; x is clamped
// to that range (NaN gives an unspecified value).
inline V4f ExpNeg4(V4f x) {
  const V4f zero = SplatV4f(0), top = SplatV4f(87);
  x = x < zero ? zero : x;
  x = x > top ? top : x;
  // exp(-x) = 2^-k * exp(r), k = round(x / ln 2), r = k ln 2 - x in [-0.35, 0.35]; ln 2 in two
  // parts (the first with few mantissa bits, so k * kLn2Hi is exact) keeps r exact to float
  // rounding also for large x. exp(r) by its Taylor series to r^6 (error below 1.3e-7).
  constexpr float kLog2e = 1.44269504f, kLn2Hi = 0.693145751953125f, kLn2Lo = 1.42860677e-06f;
  constexpr float kRound = 12582912.0f;  // 1.5 * 2^23: adding it rounds to an integer
  const V4f k = (x * kLog2e + kRound) - kRound;
  const V4f r = (k * kLn2Hi - x) + k * kLn2Lo;
  constexpr float c2 = 1.0f / 2, c3 = 1.0f / 6, c4 = 1.0f / 24, c5 = 1.0f / 120, c6 = 1.0f / 720;
  const V4f p = 1.0f + r * (1.0f + r * (c2 + r * (c3 + r * (c4 + r * (c5 + r * c6)))));
  const V4i biased = (127 - __builtin_convertvector(k, V4i)) << 23;  // 2^-k, k <= 126
  return p * std::bit_cast<V4f>(biased);
}

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_FAST_EXP_H_

#include "core/pipeline/time_estimate.h"

#include <algorithm>
#include <cmath>

namespace membrane {

double GridSecondsFloor(int64_t voxels, int threads) {
  return 20e-9 * static_cast<double>(voxels) / std::max(threads, 1);
}

double EncodeSecondsFloor(int quantization_bits) {
  if (quantization_bits <= 0) return 0;
  return 25e-9 * std::ldexp(1.0, quantization_bits);
}

}  // namespace membrane

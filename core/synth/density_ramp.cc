#include "core/synth/density_ramp.h"

#include <algorithm>
#include <cmath>

namespace membrane {

DensityRamp::DensityRamp(const Vec3d& direction, const Interval& extent, double ratio)
    : direction_(direction), extent_(extent), log_ratio_(std::log(ratio)) {}

double DensityRamp::Acceptance(const Vec3d& p) const {
  if (log_ratio_ == 0.0) return 1.0;
  const double s = (Dot(p, direction_) - extent_.lo) / (extent_.hi - extent_.lo);
  const double ramp = (s - 0.1) / 0.8;
  // The flat ends skip the exponential (and clamp points outside the extent).
  if (ramp >= 1.0) return 1.0;
  return std::exp(log_ratio_ * (std::max(ramp, 0.0) - 1.0));
}

}  // namespace membrane

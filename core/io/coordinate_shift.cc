#include "core/io/coordinate_shift.h"

#include <cmath>

#include "absl/strings/str_format.h"
#include "core/io/binary_scalar.h"

namespace membrane {

void CoordinateShift::Fix(double x, double y, double z) {
  if (fixed_ || !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) return;
  fixed_ = true;
  const double first[3] = {x, y, z};
  for (int k = 0; k < 3; ++k) {
    const double m = std::fabs(first[k]);
    origin_[k] = m >= kShiftFrom && m <= kShiftUpTo ? std::round(first[k]) : 0.0;
  }
}

Point3f CoordinateShift::Narrow(double x, double y, double z) {
  Fix(x, y, z);
  return {NarrowToFloat(x - origin_[0]), NarrowToFloat(y - origin_[1]),
          NarrowToFloat(z - origin_[2])};
}

Point3f CoordinateShift::NarrowStored(double x, double y, double z, bool binary_float32) {
  if (binary_float32) return {NarrowToFloat(x), NarrowToFloat(y), NarrowToFloat(z)};
  return Narrow(x, y, z);
}

absl::Status CheckOriginFitsFormat(const Origin3d& origin, FileFormat format, FileUse use) {
  if (origin == Origin3d{0, 0, 0} || (format != FileFormat::kStl && format != FileFormat::kDrc))
    return absl::OkStatus();
  const absl::string_view keep =
      use == FileUse::kWriteMesh ? ".ply or .obj" : ".ply, .obj or .xyz";
  return absl::InvalidArgumentError(absl::StrFormat(
      "the input's coordinates lie around (%.17g, %.17g, %.17g), too far from 0 for the float32 "
      "positions of %s; write %s, which keep them in double",
      origin[0], origin[1], origin[2], FormatName(format), keep));
}

}  // namespace membrane

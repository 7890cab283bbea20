#include "core/pipeline/grid_box.h"

#include <cmath>
#include <utility>

#include "absl/strings/str_format.h"

namespace membrane {
namespace {

constexpr char kAxes[] = "xyz";

}  // namespace

absl::Status CheckGridBox(const Box3d& box) {
  for (int d = 0; d < 3; ++d) {
    for (const auto& [side, value] : {std::pair{"min", box.min[d]}, std::pair{"max", box.max[d]}}) {
      if (!std::isfinite(value)) {
        return absl::InvalidArgumentError(
            absl::StrFormat("grid_box %c: %s %g is not finite", kAxes[d], side, value));
      }
    }
    // A flat or inverted box bounds no solid: CheckedBounds refuses such points too.
    if (!(box.min[d] < box.max[d])) {
      return absl::InvalidArgumentError(absl::StrFormat(
          "grid_box %c: min %.17g is not below max %.17g", kAxes[d], box.min[d], box.max[d]));
    }
  }
  return absl::OkStatus();
}

absl::Status CheckGridBoxHoldsPoints(const Box3d& box, const Box3d& points, double voxel_size) {
  const double allowed = voxel_size / kGridBoxStepsPerVoxel;
  for (int d = 0; d < 3; ++d) {
    const double below = box.min[d] - points.min[d];
    const double above = points.max[d] - box.max[d];
    if (below <= allowed && above <= allowed) continue;
    const bool low = below > allowed;
    return absl::InvalidArgumentError(absl::StrFormat(
        "grid_box does not contain the points: their %c %s %.9g is %.3g %s the box's %.9g, more "
        "than the %.3g (1/%d of the voxel size %g) allowed for the upload's quantization",
        kAxes[d], low ? "min" : "max", low ? points.min[d] : points.max[d],
        low ? below : above, low ? "below" : "above", low ? box.min[d] : box.max[d], allowed,
        kGridBoxStepsPerVoxel, voxel_size));
  }
  return absl::OkStatus();
}

}  // namespace membrane

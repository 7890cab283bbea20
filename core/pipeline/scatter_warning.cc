#include "core/pipeline/scatter_warning.h"

#include "absl/strings/str_format.h"

namespace membrane {
namespace {

constexpr double kSizeStep = 1.25;

// At least kSuggestedDensityRatio, counting "every voxel holds two or more" as dense.
bool ScanLike(const PointDensity& d) {
  return d.voxels_with_more_points >= kSuggestedDensityRatio * d.voxels_with_one_point;
}

}  // namespace

bool Scattered(const PointDensity& d) {
  return d.voxels_with_one_point > 0 && d.ratio() < kScatteredDensityRatio;
}

std::optional<std::string> ScatterWarning(absl::Span<const Point3f> points, const Box3d& bounds,
                                          double voxel_size, const PointDensity& density,
                                          const CancelToken& cancel, int size_steps) {
  if (!Scattered(density)) return std::nullopt;
  const std::string what = absl::StrFormat(
      "the points scatter about their surface by more than a voxel: density ratio %.3g, where "
      "scans of a surface give 1-2, and such a membrane can have false handles or shells; ",
      density.ratio());
  double size = voxel_size;
  PointDensity d = density;
  for (int k = 1; k <= size_steps; ++k) {
    if (cancel.cancelled()) return std::nullopt;
    size *= kSizeStep;
    d = MeasurePointDensity(points, bounds, size);
    if (ScanLike(d)) {
      return what + absl::StrFormat("a voxel size of %.3g (%.2gx) gives a ratio of %.2g", size,
                                    size / voxel_size, d.ratio());
    }
  }
  return what + absl::StrFormat(
                    "even a voxel size of %.3g (%.2gx) gives only %.2g: do the points sample "
                    "one surface?",
                    size, size / voxel_size, d.ratio());
}

}  // namespace membrane

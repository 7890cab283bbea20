// A warning for clouds whose points scatter about their surface by more than a voxel (noisy
// scans, or no surface at all). The paper's density ratio (section 4.3: voxels holding two
// points or more over voxels holding one) is 1.0-1.9 for every real scan of ../shared/data and
// every clean test shape at formula (1)'s voxel size; scattered points fill voxels one by one
// and push it down. On spheres with radial noise the membrane then gets false handles: ratio
// 0.37 kept genus 0, 0.19 gave genus 1 and 0.14 genus 11, and a voxel size where the ratio
// reached 2 gave genus 0 again (docs/engine-decisions.md, "Scattered points").
#ifndef MEMBRANE_CORE_PIPELINE_SCATTER_WARNING_H_
#define MEMBRANE_CORE_PIPELINE_SCATTER_WARNING_H_

#include <optional>
#include <string>

#include "absl/types/span.h"
#include "core/base/cancel_token.h"
#include "core/engine/point_density.h"
#include "core/geometry/point_cloud.h"

namespace membrane {

// Below this density ratio the points count as scattered: half the lowest real scan's.
inline constexpr double kScatteredDensityRatio = 0.5;
// The ratio the suggested voxel size must reach: a real scan's.
inline constexpr double kSuggestedDensityRatio = 2.0;
// Sizes tried for the suggestion: 1.25^k times the voxel, k = 1..steps (10: up to 9.3x).
inline constexpr int kScatterSizeSteps = 10;

// True when `d` counts as scattered: some voxel holds a single point and the ratio is below
// kScatteredDensityRatio. (A cloud whose every voxel holds two points or more is dense, not
// scattered, although Voxelization reports its ratio as 0.)
bool Scattered(const PointDensity& d);

// nullopt unless Scattered(`density`), Voxelize's counts for `points` in `bounds` at
// `voxel_size` (model units). Else one sentence for the user: the ratio, what it means for the
// topology, and the smallest voxel size among 1.25^k * voxel_size (k = 1..size_steps) whose
// ratio reaches kSuggestedDensityRatio, or that none does. Measuring a size costs a sort of the
// points' voxel indices (about 0.1 s per million points), only for scattered clouds; `cancel`
// is looked at between sizes, and nullopt returned once it fired.
std::optional<std::string> ScatterWarning(absl::Span<const Point3f> points, const Box3d& bounds,
                                          double voxel_size, const PointDensity& density,
                                          const CancelToken& cancel,
                                          int size_steps = kScatterSizeSteps);

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_SCATTER_WARNING_H_

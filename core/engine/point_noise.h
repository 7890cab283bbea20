// How far a cloud's points scatter across their surface: the noise that decides how fine a
// voxel the data can carry (paper section 3: voxels of the order of the acquisition error).
// Formula (1) follows the points' count alone; a dense scan whose range noise exceeds a few
// tenths of that voxel fills a fuzzy skin of hard voxels that the membrane cannot close
// without spurious handles (docs/engine-decisions.md, "The default voxel follows the points'
// noise").
#ifndef MEMBRANE_CORE_ENGINE_POINT_NOISE_H_
#define MEMBRANE_CORE_ENGINE_POINT_NOISE_H_

#include "absl/types/span.h"
#include "core/base/cancel_token.h"
#include "core/geometry/point_cloud.h"

namespace membrane {

// Boxes sampled by MeasurePointNoise, and the fewest fitted boxes that make an estimate.
inline constexpr int kNoiseBoxes = 1500;
inline constexpr int kNoiseMinFittedBoxes = 32;

struct PointNoise {
  // The median, over the boxes fitted, of the points' root-mean-square distance from their
  // least-squares height quadric (model units); 0 when fewer than kNoiseMinFittedBoxes boxes
  // had enough points to fit.
  double sigma = 0;
  int fitted_boxes = 0;
};

// The largest noise, in voxels, that the default voxel size leaves: where the points scatter by
// more, the voxel grows until they scatter by this much. The 150k-point 8-view scans of
// ../shared/data read 0.10-0.12 of their formula-(1) voxel and keep it; the same scanner's 1M
// points read 0.26-0.30, where the formula-(1) membrane of the bunny has 4 false handles.
inline constexpr double kVoxelNoiseShare = 0.15;

// The points' noise across their surface, measured in `boxes` axis-aligned cubes of half-width
// `half_width` (model units, > 0) centred on points spread evenly through `points` (the
// (k + 1/2) n / boxes-th, so the same cloud gives the same estimate). In each cube holding at
// least 12 points (the first 256 read, when it holds more), a height quadric is fitted over the
// points' best plane, and its residual taken with its 6 degrees of freedom discounted. The
// quadric takes up the surface's curvature, so a smooth clean surface reads near 0 and range
// noise reads as itself; the median ignores the cubes across two sheets (a thin part), an edge
// or a border. A half-width of two formula-(1) voxels holds 20-60 points of a scan: small enough
// that the two sides of a thin part rarely share a cube, large enough for the fit. Cost: one
// pass over the points with a hash lookup each, and the fits (0.25 CPU s at 10M points). Asks
// `cancel` every 65536 points and returns {} once it fired.
PointNoise MeasurePointNoise(absl::Span<const Point3f> points, const Box3d& bounds,
                             double half_width, const CancelToken& cancel = CancelToken::Never(),
                             int boxes = kNoiseBoxes);

// The default voxel size for a cloud whose formula-(1) size is `formula_size` and whose noise is
// `noise`: the larger of formula_size and noise.sigma / kVoxelNoiseShare.
double NoiseAwareVoxelSize(double formula_size, const PointNoise& noise);

// Whether the noise chose `voxel_size`: a formula-(1) size was computed (`formula_size` > 0; a
// run given its size records 0) and the voxel is coarser than it.
bool VoxelRaisedForNoise(double formula_size, double voxel_size);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_POINT_NOISE_H_

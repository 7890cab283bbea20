// The Gaussian-weighted plane sums (and, in a vertex's frame, the height-field sums of
// height_quadric.h) of the points near one surface vertex, in float, four points
// at a time: the inner loop of the fit's target (point_fitting.h; membrane-quality.md recipe 3
// step 5, "gather points within 2 voxels, Gaussian weights"). Point by point in double it would be
// half of the fit. The weights are a smoothing kernel: float's 1e-7 relative error moves a
// target by far less than the float32 rounding of the vertex it is written to.
#ifndef MEMBRANE_CORE_MESH_NEAR_POINT_SUMS_H_
#define MEMBRANE_CORE_MESH_NEAR_POINT_SUMS_H_

#include <array>
#include <cstdint>
#include <vector>

#include "core/geometry/point_cloud.h"
#include "core/mesh/crease_fit.h"
#include "core/mesh/height_quadric.h"
#include "core/mesh/plane_fit.h"
#include "core/mesh/point_row_grid.h"

namespace membrane {

// Lengths in model units; offsets d = point - origin.
struct NearPointWeights {
  Point3f origin;                // a float32 vertex: each offset is one rounded difference
  float radius2 = 0;             // only points with |d|^2 <= radius2 count
  float inv_2s2 = 0;             // 1 / (2 sigma^2): the Gaussian across the normal
  float inv_2n2 = 0;             // 1 / (2 normal_sigma^2): along it (= inv_2s2: isotropic)
  std::array<float, 3> normal{};  // unit; ignored when isotropic
};

struct NearPointResult {
  PlaneFitAccumulator acc;  // sums over the points within the radius, offsets as coordinates
  int count = 0;            // how many points are within the radius
};

// The instructions the sums are computed with: the same bits with either.
enum class SumsInstructions {
  kBest,      // the widest the processor has (AVX-512 F and VL on x86-64), else the baseline's
  kBaseline,  // the build's baseline instruction set
};

// Whether kBest runs other instructions than kBaseline on this processor.
bool HasWideSumsInstructions();

// Over the points of `grid` that ForEachRun(origin, radius) lists, those with |d|^2 <= radius2,
// weighted w = exp(-(|d|^2 - (d.n)^2) inv_2s2 - (d.n)^2 inv_2n2): the accumulated plane sums
// (in float, returned in double) and their count. A grid with weights (ws(): cell means and
// their point counts, point_cell_means.h) multiplies each w by the stored weight, and counts
// the stored weights.
NearPointResult WeighNearPoints(const PointRowGrid& grid, double radius,
                                const NearPointWeights& weights,
                                SumsInstructions instructions = SumsInstructions::kBest);

// The same weights in a vertex's frame: each offset d = point - origin (model units) becomes
// (u, v, h) = (d.axes[0], d.axes[1], d.axes[2]), the axes orthogonal with a common length
// 1 / scale (so u, v, h are in units of `scale`: voxels for the fit), h along the normal.
struct FrameWeights {
  Point3f origin;
  std::array<std::array<float, 3>, 3> axes{};  // tangent, tangent, normal
  float radius2 = 0;                           // in frame units
  float inv_2s2 = 0;                           // in frame units, across the normal
  float inv_2n2 = 0;                           // in frame units, along it
};

// Over the points that ForEachRun(origin, radius) lists (radius in model units), those with
// u^2 + v^2 + h^2 <= radius2, weighted w = exp(-(u^2 + v^2) inv_2s2 - h^2 inv_2n2): the height
// field sums of height_quadric.h (in float, returned in double) and their count; a grid with
// weights as WeighNearPoints weighs them.
HeightFieldSums WeighNearPointsInFrame(const PointRowGrid& grid, double radius,
                                       const FrameWeights& weights,
                                       SumsInstructions instructions = SumsInstructions::kBest);

// The points WeighNearPointsInFrame weighs, one by one in `out` (cleared first): (u, v, h) and
// w = exp(-(u^2 + v^2) inv_2s2 - h^2 inv_2n2), times the stored weight on a grid of cell means;
// points of weight 0 are left out. In double, for the few vertices whose points are fitted
// again one by one (crease_fit.h).
void CollectNearPointsInFrame(const PointRowGrid& grid, double radius, const FrameWeights& weights,
                              std::vector<FramePoint>& out);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_NEAR_POINT_SUMS_H_

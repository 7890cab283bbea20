// A dense cloud's points merged per small cell into their mean and count, for the fit's
// weighed sums (point_fitting.h): on a scan with tens of points per voxel, the Gaussian and
// height-field sums over a cell's points are close to those of its mean weighted by its count,
// and the fit then reads a few means per voxel instead of every point.
#ifndef MEMBRANE_CORE_MESH_POINT_CELL_MEANS_H_
#define MEMBRANE_CORE_MESH_POINT_CELL_MEANS_H_

#include <vector>

#include "absl/types/span.h"
#include "core/geometry/point_cloud.h"

namespace membrane {

struct PointCellMeans {
  std::vector<Point3f> means;  // one per occupied cell
  std::vector<float> counts;   // the points of each (exact integers)
};

// Input: `points` (fewer than 2^32), `cell` > 0 in model units. Output: per occupied cell of a
// PointRowGrid of `points` with that cell size (grown as PointRowGrid grows it for a huge box),
// in its storage order, the mean of the cell's points (summed in double, in their stable
// order, rounded to float) and their count. A cell holding one point gives that point itself.
// The build runs on `threads` (<= 1: the calling thread); the result does not depend on it.
PointCellMeans MeanPerCell(absl::Span<const Point3f> points, double cell, int threads);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_POINT_CELL_MEANS_H_

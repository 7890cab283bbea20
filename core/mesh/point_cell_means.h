// A dense cloud's points merged per small cell into their mean and count, for the fit's
// weighed sums (point_fitting.h): on a scan with tens of points per voxel, the Gaussian and
// height-field sums over a cell's points are close to those of its mean weighted by its count,
// and the fit then reads a few means per voxel instead of every point.
#ifndef MEMBRANE_CORE_MESH_POINT_CELL_MEANS_H_
#define MEMBRANE_CORE_MESH_POINT_CELL_MEANS_H_

#include <vector>

#include "core/geometry/point_cloud.h"
#include "core/mesh/point_row_grid.h"

namespace membrane {

struct PointCellMeans {
  std::vector<Point3f> means;  // one per occupied cell
  std::vector<float> counts;   // the points of each (exact integers)
};

// Input: `grid` an index of the points; `split` in [1, 8]. Output: per occupied sub-cell (each
// of the grid's cells cut into split^3 cubes of edge grid.cell() / split), in the grid's cell
// order and within a cell in (z, y, x) order of its sub-cells, the mean of the sub-cell's
// points (summed in double in their stored order, rounded to float) and their count. A sub-cell
// holding one point gives that point itself. A point on a sub-cell wall goes to the sub-cell
// its coordinates' rounding gives, within its own cell.
PointCellMeans MeanPerSubCell(const PointRowGrid& grid, int split);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_POINT_CELL_MEANS_H_

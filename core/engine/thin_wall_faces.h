// Whether a run of hard voxels crosses a thin wall with data on both of its faces, read from
// what each of the run's two outside ends faces (the thick-wall test's thin-part exception,
// incursion_test.h; issue 18, thin-walled cups).
#ifndef MEMBRANE_CORE_ENGINE_THIN_WALL_FACES_H_
#define MEMBRANE_CORE_ENGINE_THIN_WALL_FACES_H_

#include "core/engine/hard_voxel_points.h"
#include "core/engine/voxel_grid.h"

namespace membrane {

// Input: the outside voxels `a` and `b` at the two ends of a run of hard voxels, and the
// points.
// Returns how far apart, in voxels, the surfaces the two ends face lie: with m_a the mean of
// the points `a` faces (HardVoxelPoints::FacingPatch, radius 2, band 0.5 voxel) and n_a the
// normal of their plane, towards `a` (the plane of both patches about their own means when
// a's own points hold none, the mean of the ends' directions to their feet when neither
// does), likewise m_b and n_b: the larger of (m_a - m_b) . n_a and (m_b - m_a) . n_b. The two
// faces of a thin wall give about its thickness whatever the wall's slope to the run (each
// end's foot lies on its own face; tests/bench/2026-12-05-thin-cup.txt), one scanned surface
// seen from both sides its noise (both feet on the one sheet). -1 when an end faces no point
// or lies on its points' mean.
double FacingGap(const VoxelGrid& grid, const HardVoxelPoints& points, const Coord& a,
                 const Coord& b);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_THIN_WALL_FACES_H_

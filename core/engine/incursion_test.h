// The incursion test (paper section 4.2; algorithm-notes 7 and 15, membrane-quality recipe 1).
#ifndef MEMBRANE_CORE_ENGINE_INCURSION_TEST_H_
#define MEMBRANE_CORE_ENGINE_INCURSION_TEST_H_

#include <cstdint>

#include "core/engine/hard_voxel_points.h"
#include "core/engine/voxel_grid.h"

namespace membrane {

// Whether the outside voxels a and b are joined by a 6-path of outside voxels inside the cube
// of Chebyshev radius r around `centre` (clipped to the array): false when a or b lies outside
// the cube. A breadth-first search over at most (2r + 1)^3 voxels.
bool OutsideJoinedInCube(const VoxelGrid& grid, int64_t centre, int64_t a, int64_t b, int r);

// When a thick-wall run (or, for the facing gap, the paper's wall of one voxel) is taken for a
// thin part rather than a wall with a dig behind it (ChainRules::thick_wall_detour,
// thin_part_min_spread and thin_wall_face_*).
struct ThinPartRule {
  int detour = 0;          // radius (voxels) within which the run's ends must be joined; 0 = never
  double min_spread = 0;   // least PlaneSpread of the run's points (voxels); 0 = not read
  const HardVoxelPoints* points = nullptr;  // the input points; none: min_spread is never met
  // Least FacingGap (thin_wall_faces.h) of the ends of a run of at most face_max_run voxels,
  // in voxels, for the run to be taken as a thin part whatever the detour; 0 = not read.
  double min_face_gap = 0;
  int face_max_run = 2;
};

// The paper's test on the hard or frozen, non-outside voxel at `index`: for some axis, its two
// face neighbours A and B are outside with different generations and are not local-arc
// connected (no 6-path of outside voxels joins them inside the 3x3x3 block around the voxel),
// and, when thin.min_face_gap > 0 and thin.face_max_run >= 1, the surfaces A and B face do not
// lie that far apart (FacingGap): a wall of one voxel with data on both of its faces is a
// thin part, as ThickWallIncursion's runs (a thin-walled cup at twice its wall's voxel).
// `index` must lie at least one voxel from the array border.
bool PaperIncursion(const VoxelGrid& grid, int64_t index, const ThinPartRule& thin = {});

// The thick-wall extension: for some axis, the run of hard or frozen non-outside voxels through
// the voxel (at most `max_run` long) is longer than one, the voxels A and B just beyond its ends
// are outside with different generations, no 6-path of outside voxels joins A and B inside
// the box spanning A..B along the axis and one voxel either side across it, and the run is no
// thin part. It is one (`thin`) when thin.detour > 0, A and B are joined through the outside
// inside the cube of radius thin.detour around the voxel (A or B outside that cube counts as
// not joined; the cube is clipped to the array), and, when thin.min_spread > 0, the points of
// the box spanning the run along the axis and one voxel either side across it lie at least
// thin.min_spread voxels from their best plane (HardVoxelPoints::PlaneSpread): data on both
// sides of the run, the two faces of a leg, a horn or a belt. A scanned wall at the rim of a
// data hole is joined around too, but its points lie on one surface: the test fires there, so
// that plates do not dig behind it. A run of at most thin.face_max_run voxels is also a thin
// part, joined around or not, when thin.min_face_gap > 0 and the surfaces its two ends A and B
// face lie at least that far apart (FacingGap): a wall with data on both faces, such as a
// cup's, whose two sides meet only over its rim, far beyond any detour. `index` must lie at least max_run voxels from the array
// border (the padding guarantees it for hard voxels when max_run <= 3).
bool ThickWallIncursion(const VoxelGrid& grid, int64_t index, int max_run,
                        const ThinPartRule& thin);

// Either test fires (the thick one only when max_run > 1).
inline bool IncursionAt(const VoxelGrid& grid, int64_t index, int max_run,
                        const ThinPartRule& thin) {
  return PaperIncursion(grid, index, thin) ||
         (max_run > 1 && ThickWallIncursion(grid, index, max_run, thin));
}

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_INCURSION_TEST_H_

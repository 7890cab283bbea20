// The membrane of the engine tests' random grids: boundary states beside the outside and a
// scatter of voxels that plates must work around.
#ifndef MEMBRANE_TESTS_SUPPORT_RANDOM_MEMBRANE_H_
#define MEMBRANE_TESTS_SUPPORT_RANDOM_MEMBRANE_H_

#include <cstdint>
#include <random>

#include "core/engine/voxel_grid.h"

namespace membrane::testing {

// Input: `grid` with its outside voxels set (the padding among them) and the rest inside.
// Effect: every voxel that is not outside, off the array border and beside an outside voxel
// becomes boundary (hard or frozen at random, 4% and 3%, else soft), then grid.size() /
// `scatter_divisor` voxels drawn at random, those off the padding, become outside or boundary
// soft at random. The padding stays outside, as on every grid the shrink is given: the chains'
// floods read a voxel's neighbours without a bounds check. Draws from `rng` in a fixed order,
// so a seed gives one grid.
void MarkRandomMembrane(VoxelGrid& grid, std::mt19937& rng, int64_t scatter_divisor);

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_SUPPORT_RANDOM_MEMBRANE_H_

// The shrink's big plates on a coarser grid (docs/engine-decisions.md, "Big plates on a
// coarser grid"; ShrinkOptions::coarse_plates).
//
// The first generations move a membrane that is far from the data, and on a dense grid each
// of them passes over the whole volume (a 10M-point torus: 2.2e9 voxels a pass, plates 646 to
// 41 about 60% of the generations' time). A plate of n voxels is a plate of ceil(n / k) voxels
// on the grid k times coarser (a coarse voxel hard when any of its fine voxels is): those
// generations run there, on k^-3 of the voxels, and the coarse outside they reach is lifted
// to the grid, where the generations go on from the next plate.
#ifndef MEMBRANE_CORE_ENGINE_COARSE_PLATES_H_
#define MEMBRANE_CORE_ENGINE_COARSE_PLATES_H_

#include <cstdint>
#include <vector>

#include "absl/status/status.h"
#include "absl/types/span.h"
#include "core/base/cancel_token.h"
#include "core/engine/membrane_shrinker.h"
#include "core/engine/shrink_options.h"
#include "core/engine/voxel_grid.h"

namespace membrane {

// How many leading generations of `sizes` (the grid's plate sizes, first to last) run on the
// coarser grid for a grid of `grid_voxels` voxels: those whose plate is at least
// options.coarse_plates.min_plate and options.interior_guard.band_release_below, and before
// generation `limit` (the handle retry's first). 0 when the grid is under
// coarse_plates.min_voxels (or that is 0), the schedule is not halving (the coarse plates of
// the halving schedule are its own halving from the first), or the silhouette pre-shrink is on
// (the coarse grid is built from a grid with no outside voxel in its data region).
size_t CoarseGenerationCount(int64_t grid_voxels, absl::Span<const int> sizes,
                             const ShrinkOptions& options, size_t limit);

// Input: `grid` as Voxelize() left it, the interior guard's frozen voxels allowed; `sizes` and
// `labels` its generations' plate sizes and labels; count <= CoarseGenerationCount's.
// Builds the grid k = coarse_plates.factor times coarser (CoarseGrid) and runs its generations
// of plates ceil(sizes[g] / k), g < count, with `options` less the interior guard, the handle
// retry and the silhouette pre-shrink (closed forms where they hold, chains elsewhere).
// Appends a row per generation to `rows` (generation and plate_size the grid's, level k, the
// counters the coarse grid's) and passes each to `on_generation` (may be empty) as it ends.
// Then lifts the coarse outside to `grid` (LiftCoarseOutside). Returns the generations run
// there (`count`; the grid's go on from the next), the voxels lifted and factor k (all 0 when
// count is). After it the membrane invariants hold but Property 3. Cancelled when `cancel`
// fires (the grid is then as before the lift); Internal if the coarse plates are not
// ceil(sizes[g] / k).
absl::StatusOr<CoarsePlatesStats> RunCoarsePlates(VoxelGrid& grid, const ShrinkOptions& options,
                                                  absl::Span<const int> sizes,
                                                  absl::Span<const int> labels, size_t count,
                                                  const CancelToken& cancel,
                                                  const GenerationCallback& on_generation,
                                                  std::vector<GenerationStats>& rows);

// Every fine voxel of the data region in an outside voxel of the data region of `coarse`
// (CoarseGrid(grid, k, ...) shrunk some generations) becomes outside, labelled
// fine_labels[its coarse voxel's label]; then every fine voxel left INSIDE with an outside
// 26-neighbour becomes boundary, keeping its hardness. A coarse outside voxel holds no hard
// fine voxel, and 6-connected coarse outside lifts to 6-connected fine outside, so the
// membrane invariants of `grid` hold after it when they held on `coarse` (Property 3 aside).
// A coarse z plane a task on `threads`. Returns how many fine voxels became outside.
int64_t LiftCoarseOutside(VoxelGrid& grid, const VoxelGrid& coarse, int k,
                          absl::Span<const int> fine_labels, int threads);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_COARSE_PLATES_H_

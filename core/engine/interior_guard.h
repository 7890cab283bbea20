// The interior of a scanned solid held by a coarser membrane (docs/engine-decisions.md,
// "Interiors held by a coarser membrane").
//
// On dense, noisy scans (a million points and up at the formula-(1) voxel) the skin's data is
// porous and fuzzy, and the plates get into the solid through its unscanned base and its
// sparse patches: they hollow the interior, the chains carve and undo it plate by plate
// (a 1M-point scan's shrink doubles; a 10M-point one's takes hours), and where the hollow
// meets the skin from inside handles are left. The same scan voxelized `factor` times coarser
// has a closed skin there, and its membrane (factor^-3 of the voxels, shrunk and refilled
// the same way) keeps the interior. The fine voxels of that interior are frozen before the
// first generation, so the fine plates stop at it as at a wall.
#ifndef MEMBRANE_CORE_ENGINE_INTERIOR_GUARD_H_
#define MEMBRANE_CORE_ENGINE_INTERIOR_GUARD_H_

#include <array>
#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "core/base/cancel_token.h"
#include "core/engine/voxel_grid.h"

namespace membrane {

struct ShrinkOptions;

struct InteriorGuardOptions {
  bool enabled = true;
  // A coarse voxel is factor^3 fine voxels, 2..4.
  int factor = 4;
  // The guard runs when the coarse grid's longest data axis has at least this many voxels:
  // on smaller grids the plates that fit through the scan's gaps carve little, and the gap
  // refill puts it back.
  int min_coarse_axis = 96;
  // A coarse voxel is interior when at most this many of its 6 axis rays reach the coarse
  // outside before a hard voxel: two data holes seen (an unscanned base and a sparse side),
  // not a web or a plate left frozen in a corner, which sees the outside on more.
  int max_open_rays = 2;
  // The band is released before the first generation whose plate is below this size
  // (ReleaseGuardedBand); 0: kept to the end of the generations. Through the plates of 3 and
  // 4: a scan's skin at the voxel is porous (scan lines wider apart than a voxel, fuzz), and
  // the plates of that size that meet its inner side from a hollow made through the base
  // riddle it with handles (docs/engine-decisions.md, "Interiors held by a coarser membrane").
  int band_release_below = 3;
  // The guard runs only where the data are one piece (FindDataPieces: fewer than two
  // 26-components of hard voxels holding ShrinkOptions::separation.min_piece_fraction of them
  // each). The coarse grid joins pieces fewer than `factor` voxels apart, and its membrane,
  // kept out of their gaps, holds the space between them as an interior.
  bool one_piece_only = false;
};

// On a grid whose voxel the points' noise chose (point_noise.h, VoxelRaisedForNoise) the scan
// is dense for its voxel whatever the grid's width: dense scans get grids 250-350 voxels wide
// at 1M to 50M points, under the 4 x 96 at which min_coarse_axis lets the guard run, and their
// plates hollow the interior through the unscanned base as formula (1)'s do at 700k points.
// Such a grid is guarded from this coarse width (128 fine voxels). Not lower: a width of 16,
// measured with a second guard level on a coarse grid 16 voxels wide (docs/engine-decisions.md,
// "Dense scans' interiors"), gave the 1M bunny genus [2] where 32 gives [0].
inline constexpr int kDenseScanMinCoarseAxis = 32;
// ... and its core sees the outside on one ray at most: a dense scan's skin is fuzzy but seen
// all round, and a second open ray gives its 1M-point scans a core that reaches further into
// the skin (bunny Chamfer 0.0602 -> 0.0614, spot 0.0143 -> 0.0154).
inline constexpr int kDenseScanMaxOpenRays = 1;

// `options` for a grid whose voxel the points' noise chose: min_coarse_axis at most
// kDenseScanMinCoarseAxis, max_open_rays at most kDenseScanMaxOpenRays, one_piece_only
// (objects 5 voxels apart, cow-spot-belt's, are held apart by 1.25 coarse voxels), the rest
// (enabled included) as given.
InteriorGuardOptions DenseScanGuard(InteriorGuardOptions options);

// The coarse voxels of the band GuardInteriors froze, to release them later.
struct GuardedBand {
  int factor = 0;
  std::array<int, 3> coarse_dims{};
  std::vector<int64_t> coarse_voxels;  // indices in the coarse grid, increasing
  // Whether the grid holds the band frozen: ReleaseGuardedBand clears it, and a shrink that
  // restores a grid saved before the release sets it again.
  bool held = false;
};

struct InteriorGuardStats {
  int levels = 0;             // coarse membranes built: 1 when the guard ran, else 0
  int64_t core_voxels = 0;    // coarse voxels of the solid with no hard voxel in their block
  int64_t frozen_voxels = 0;  // fine voxels frozen, the band's included
  int64_t band_frozen = 0;    // fine voxels of the band the core's wave reached first
  int64_t released_voxels = 0;  // still inside after the generations (ReleaseInteriorGuard)
  double seconds = 0;
};

// Input: a voxelized grid before its first generation (padding outside, the data region
// inside soft or hard, its outer layer boundary). Builds the grid `factor` times coarser (a
// coarse voxel hard when any of its fine voxels is) and shrinks it with `options` (without an
// interior guard of its own, and without points: the thin-part exception, the split and the
// hole opening are off there; no dents). Then it freezes:
//   - the core: the fine INSIDE soft voxels of every coarse voxel of the coarse solid with no
//     hard voxel in its 3x3x3 block and at most max_open_rays of its 6 axis rays reaching the
//     coarse outside before a hard voxel (an interior seen through a data hole or two; a
//     web or a plate left frozen in a corner sees the outside on more);
//   - the band: the fine INSIDE soft voxels of the other coarse solid voxels that a
//     breadth-first wave from the core reaches through soft voxels before a wave from the
//     coarse outside does, never a voxel next to a hard one (so the skin and its pores are
//     left as they are).
// Does nothing when the guard is off, the coarse grid's longest axis is under
// min_coarse_axis, the data are two pieces or more under one_piece_only, or the coarse solid
// has no core.
// Errors: Cancelled when `cancel` fires (the shrink is then abandoned; the grid may hold part
// of the frozen voxels); the coarse shrink's.
absl::StatusOr<InteriorGuardStats> GuardInteriors(VoxelGrid& grid, const ShrinkOptions& options,
                                                  const CancelToken& cancel,
                                                  GuardedBand* band = nullptr);

// Turns the band's frozen INSIDE voxels back to INSIDE soft (a chain freezes boundary voxels
// only, so these are the guard's), leaving the core frozen: from the plate size
// InteriorGuardOptions::band_release_below down, the plates that reach the skin work there as
// they would without the guard. Does nothing unless band.held, which it clears. Runs on
// `threads` (>= 1), a range of the band's coarse voxels a task: the same grid for any count.
// Returns how many voxels it released.
int64_t ReleaseGuardedBand(VoxelGrid& grid, GuardedBand& band, int threads = 1);

// After the generations: every voxel still INSIDE and frozen is one GuardInteriors froze (a
// chain freezes boundary voxels only, and a boundary voxel never turns inside again); they
// become INSIDE soft, so that the passes after the generations read the interior as they
// would without the guard. Frozen boundary voxels stay frozen (Property 3). Runs on
// `threads` (>= 1), a slab of the grid a task. Returns how many voxels it released.
int64_t ReleaseInteriorGuard(VoxelGrid& grid, int threads);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_INTERIOR_GUARD_H_

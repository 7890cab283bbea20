// The options of the discrete membrane shrinking (membrane_shrinker.h). The chain rules and the
// guard sizes are the structs the chains and the guard take themselves (contraction.h,
// topology_guard.h): a generation passes them on whole.
#ifndef MEMBRANE_CORE_ENGINE_SHRINK_OPTIONS_H_
#define MEMBRANE_CORE_ENGINE_SHRINK_OPTIONS_H_

#include <array>
#include <cstdint>

#include "absl/status/status.h"
#include "core/engine/contraction.h"
#include "core/engine/local_snapshot.h"
#include "core/engine/gap_refill.h"
#include "core/engine/piece_separation.h"
#include "core/engine/hole_opening.h"
#include "core/engine/interior_guard.h"
#include "core/engine/plate_schedule.h"
#include "core/engine/topology_guard.h"

namespace membrane {

// The handle retry (docs/engine-decisions.md, handle_retry.h): when the shrink ends with
// handles, the generations from the first one that made a removal the strict rules refuse run
// again under those rules: tunnels away from the data only from tunnel_min_plate, short-loop
// tunnels only from short_loop_min_plate and wall notches only from wall_notch_min_plate (0:
// none; never below the guard's own sizes). The result with fewer handles and no fewer shells
// is kept, unless what it closed is a membrane across a scanned hole: at least max_hard_rim of
// the voxels bordering it are hard (> 1: never refused on that ground).
struct HandleRetryOptions {
  bool enabled = true;
  int tunnel_min_plate = 7;
  // 5, the default guard's tunnel size: below it the strict rules open no tunnel at all, so a
  // handle the plates of 4 notched into a web across missing data is retried as those of 2
  // and 3 are (tests/bench/2026-12-05-dense-genus.txt).
  int short_loop_min_plate = 5;
  int wall_notch_min_plate = 5;
  double max_hard_rim = 0.75;
};

// The big plates on a coarser grid (docs/engine-decisions.md, "Big plates on a coarser grid",
// coarse_plates.h): on a grid of at least min_voxels voxels, the leading generations whose
// plate is at least min_plate run with plates ceil(n / factor) on the grid `factor` times
// coarser, whose outside is then lifted to the grid; the rest run on the grid. Only with the
// halving schedule and no silhouette pre-shrink; never for the generations from the handle
// retry's first or the guarded band's release on.
struct CoarsePlatesOptions {
  int64_t min_voxels = int64_t{1} << 30;  // 0: never
  int factor = 4;                          // 2..4
  int min_plate = 41;                      // >= 8
};

struct ShrinkOptions {
  PlateSchedule schedule = PlateSchedule::kHalving;
  int initial_plate = 0;            // 0: from the grid (Algorithm 1)
  ChainRules chain;                 // depth bound, thick-wall run, guard on or off
  GuardSizes guard;                 // algorithm-notes 12
  // The guard's object_tunnel_plate on a grid: its data box's longest axis over this (0:
  // guard.object_tunnel_plate as given, by default none). A scan's unseen patches and the
  // gaps of its sparse parts grow with the grid: at 3M points plates of 25, 13 and 7 cut the
  // bunny scan's inside, seen through its base's holes, into handles (55 at 10M). Below a
  // twenty-fourth of the object a tunnel needs data around it (docs/engine-decisions.md,
  // "Tunnels small for the object need data around them").
  int tunnel_axis_ratio = 24;
  int closed_form_min_plate = 8;    // generations with n >= this try the closed form; 0 = never
  // A closed form adding at most one voxel per this many of the grid applies and checks its
  // result voxel by voxel, others by whole-grid planes (the same result); 0 = always by planes.
  int64_t closed_form_voxelwise_ratio = 256;
  // Whether a generation still tries the closed form after an earlier generation's checks
  // refused one. Off: once the checks refuse, the rest of the shrink runs chains straight
  // away. The voxels are the same (an accepted closed form is the chains' result), without
  // the sweeps of closed forms that, on every cloud measured, the checks refused again
  // (docs/engine-decisions.md, "Closed-form generations").
  bool closed_form_after_refusal = false;
  // A chain generation's passes after its first take their snapshot near the voxels the pass
  // before wrote (place_finder.h, SnapshotAfter: the same candidates and places).
  LocalSnapshotOptions local_snapshots;
  bool silhouette_preshrink = false;  // algorithm-notes 3 (Fig. 21b); off by default
  bool connect_inside_hard = true;  // section 7 post-process
  HandleRetryOptions retry;
  GapRefillOptions refill;          // channels carved through data gaps (gap_refill.h)
  PieceSeparationOptions separation;  // pieces of data joined by the shrink (piece_separation.h)
  HoleOpeningOptions holes;         // plugged holes opened from the data (hole_opening.h)
  InteriorGuardOptions interior_guard;  // the interior held by a coarser membrane (interior_guard.h)
  CoarsePlatesOptions coarse_plates;    // the big plates on a coarser grid (coarse_plates.h)
  // Threads of the word passes of the closed form and the place finder and of the state
  // counts (1..256; ReconstructionOptions::threads): split by the grid, the same DMS for any
  // count. Grids under threads_min_voxels keep them on the calling thread: their passes take
  // a few ms, where starting and joining threads on a loaded machine cost more than they gain
  // (tests/bench/2026-12-03-shrink-threads.txt). 2^27: a 2M-point torus's grid is above it,
  // a 1M-point one's below.
  int threads = 1;
  int64_t threads_min_voxels = int64_t{1} << 27;
};

// Validates options: InvalidArgument naming the field and its allowed range.
absl::Status ValidateShrinkOptions(const ShrinkOptions& options);

// The guard sizes on a grid whose data box (the grid without its padding) is `data_dims`:
// options.guard, with object_tunnel_plate the longest axis / tunnel_axis_ratio (rounded down)
// when tunnel_axis_ratio > 0.
GuardSizes GridGuardSizes(const ShrinkOptions& options, const std::array<int, 3>& data_dims);

// The guard sizes of the handle retry over the guard's sizes `guard` (options.guard or a
// grid's GridGuardSizes): tunnels away from the data only from the larger of the two tunnel
// sizes, short-loop tunnels and wall notches each only from the larger of the two sizes (off
// when either is 0); the rest as `guard`.
GuardSizes StrictGuardSizes(const ShrinkOptions& options, const GuardSizes& guard);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_SHRINK_OPTIONS_H_

// The discrete membrane shrinking (paper sections 4.3 and 7): generations of recursive
// contractions with plates of decreasing size, from the initial membrane on the exterior faces
// to the final discrete membrane set (DMS).
#ifndef MEMBRANE_CORE_ENGINE_MEMBRANE_SHRINKER_H_
#define MEMBRANE_CORE_ENGINE_MEMBRANE_SHRINKER_H_

#include <cstdint>
#include <functional>
#include <vector>

#include "absl/status/statusor.h"
#include "core/base/cancel_token.h"
#include "core/engine/plate_schedule.h"
#include "core/engine/post_process.h"
#include "core/engine/voxel_grid.h"

namespace membrane {

struct ShrinkOptions {
  PlateSchedule schedule = PlateSchedule::kHalving;
  int initial_plate = 0;            // 0: from the grid (Algorithm 1)
  int depth_bound = 3;              // algorithm-notes 14; 0 = unbounded (the paper)
  int depth_bound_max_plate = 2;    // ...applied to plate sizes up to this one
  int thick_wall_run = 3;           // algorithm-notes 15; 1 = the paper's test only
  bool topology_guard = true;       // algorithm-notes 12
  int guard_tunnel_min_plate = 5;   // notes 12: tunnels away from hard voxels from this n
  int guard_short_loop_min_plate = 3;  // below that, short-loop tunnels from this n; 0 = off
  int guard_short_loop_steps = 6;      // ...sides joined within this many outside steps
  int guard_wall_notch_min_plate = 2;  // ...and beside a wall from this n; 0 = off
  int closed_form_min_plate = 8;    // generations with n >= this try the closed form; 0 = never
  bool silhouette_preshrink = false;  // algorithm-notes 3 (Fig. 21b); off by default
  bool connect_inside_hard = true;  // section 7 post-process
  // The handle retry (docs/engine-decisions.md): when the shrink ends with handles, the
  // generations from the first plate below retry_tunnel_min_plate run again with tunnels away
  // from the data only from that plate size and short-loop tunnels only from
  // retry_short_loop_min_plate; the result with fewer handles and no fewer shells is kept,
  // unless what it closed is a membrane across a scanned hole: at least retry_max_hard_rim of
  // the voxels bordering it are hard (> 1: never refused on that ground).
  bool retry_handles = true;
  int retry_tunnel_min_plate = 7;
  int retry_short_loop_min_plate = 4;
  double retry_max_hard_rim = 0.75;
};

// What the handle retry did (ShrinkOptions::retry_handles).
struct HandleRetry {
  bool ran = false;          // the first result had handles, so the generations ran again
  bool kept = false;         // the retry's result replaced the first
  int from_generation = 0;   // first generation run again (1-based; 0: no generation qualified)
  int64_t loose_tunnels = 0; // removals from there on that the strict sizes refuse (0: no retry)
  int shells_before = 0, genus_before = 0;  // first result (genus summed over the shells)
  int shells_after = 0, genus_after = 0;    // result kept
  int64_t web_voxels = 0;    // voxels the retry left solid where the first run had outside
  double web_hard_rim = 0;   // share of hard voxels among the solid voxels bordering them
  double seconds = 0.0;      // topology counts and the generations run again
};

// One row of the paper's Tables 1 to 4 (algorithm-notes 11), plus our own counters.
struct GenerationStats {
  int generation = 0;                // 1-based
  int plate_size = 0;
  int64_t soft_voxels = 0;           // non-frozen soft boundary voxels before the generation
  int64_t started_contractions = 0;  // chains started
  int64_t backtrackings = 0;         // chains undone
  int64_t contractions = 0;          // CONTRACTION operations, undone ones included
  int64_t undone_contractions = 0;
  int64_t guard_refusals = 0;        // backtracks caused by the topology guard
  int64_t depth_refusals = 0;        // backtracks caused by the n = 1 depth bound
  // Tunnels the handle retry's strict rules would refuse (counted from the generation it would
  // start at; a closed-form generation below their tunnel size counts 1): with none, the
  // retry would repeat the same run and is skipped.
  int64_t loose_tunnels = 0;
  bool handle_retry = false;         // run again by the handle retry, whose result was kept
  int passes = 0;                    // place-finding snapshots
  bool closed_form = false;          // computed as a fixed point, without chains
  int closed_form_rounds = 0;        // rounds of its six sweeps (also when it was rejected)
  int64_t closed_form_checks = 0;    // incursion and guard tests after it
  int64_t new_outside = 0;           // voxels the generation turned outside
  double seconds = 0.0;
};

struct ShrinkResult {
  std::vector<GenerationStats> generations;
  int64_t preshrink_outside_voxels = 0;
  PostProcessStats post_process;
  HandleRetry handle_retry;
  double seconds = 0.0;
};

// Called after every generation, on the shrinking thread.
using GenerationCallback = std::function<void(const GenerationStats&)>;

// Validates options: InvalidArgument naming the field and its allowed range.
absl::Status ValidateShrinkOptions(const ShrinkOptions& options);

// Shrinks the initial membrane of `grid` (as built by Voxelize) into the final DMS.
// `generations` holds the rows of the generations kept: after a kept handle retry, the retry's
// rows (handle_retry set) replace the first run's from HandleRetry::from_generation on.
// `on_generation` sees every first-run row as it finishes, then, when a retry is kept, the
// retry's rows, each replacing the earlier row of the same generation.
// After success the membrane invariants hold (CheckMembraneInvariants) and `grid` holds the
// final DMS. `on_generation` may be empty. Cancelled when `cancel` fires (within
// milliseconds; `grid` is then a valid but unfinished DMS); InvalidArgument for bad options.
absl::StatusOr<ShrinkResult> ShrinkMembrane(VoxelGrid& grid, const ShrinkOptions& options,
                                            const GenerationCallback& on_generation,
                                            const CancelToken& cancel);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_MEMBRANE_SHRINKER_H_

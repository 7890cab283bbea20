// The discrete membrane shrinking (paper sections 4.3 and 7): generations of recursive
// contractions with plates of decreasing size, from the initial membrane on the exterior faces
// to the final discrete membrane set (DMS).
//
// MembraneShrinker runs the steps in the paper's order; each lives in a file of its own: the
// plate sizes and generation labels (Algorithm 1) in plate_schedule.h, the silhouette
// pre-shrink (algorithm-notes 3) in silhouette.h, a generation's snapshots of fitting plates
// in place_finder.h and its recursive contractions (Function 1) in contraction.h, or its
// closed form in closed_form_generation.h, the handle retry in handle_retry.h, the section 7
// post-process in post_process.h.
#ifndef MEMBRANE_CORE_ENGINE_MEMBRANE_SHRINKER_H_
#define MEMBRANE_CORE_ENGINE_MEMBRANE_SHRINKER_H_

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "core/base/cancel_token.h"
#include "core/engine/compact_states.h"
#include "core/engine/contraction.h"
#include "core/engine/hard_voxel_points.h"
#include "core/engine/interior_guard.h"
#include "core/engine/place_finder.h"
#include "core/engine/post_process.h"
#include "core/engine/shrink_options.h"
#include "core/engine/state_planes.h"
#include "core/engine/topology_guard.h"
#include "core/engine/voxel_grid.h"
#include "core/engine/work_planes.h"

namespace membrane {

// What the handle retry did (ShrinkOptions::retry, handle_retry.h).
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
  int local_passes = 0;              // of which taken near the last pass's writes only
  bool closed_form = false;          // computed as a fixed point, without chains
  int closed_form_rounds = 0;        // rounds of its six sweeps (also when it was rejected)
  int64_t closed_form_checks = 0;    // incursion and guard tests after it
  bool closed_form_voxelwise = false;  // its result was applied voxel by voxel (few new voxels)
  int64_t new_outside = 0;           // voxels the generation turned outside
  // The grid that ran it: 1 the shrink's own, k the grid k times coarser (coarse_plates.h),
  // whose voxels the counters above count.
  int level = 1;
  double seconds = 0.0;
};

// The generations run on a coarser grid (ShrinkOptions::coarse_plates, coarse_plates.h).
struct CoarsePlatesStats {
  int factor = 0;             // 0: none ran there
  int generations = 0;        // the first ones
  int64_t lifted_voxels = 0;  // voxels of the grid the lift turned outside
  double seconds = 0.0;       // the coarse grid, its generations and the lift
};

struct ShrinkResult {
  // The topology guard's sizes on this grid (GridGuardSizes): the plates from which a tunnel
  // away from the data opens, and the object's tunnel plate below which it needs data around.
  GuardSizes guard;
  std::vector<GenerationStats> generations;
  int64_t preshrink_outside_voxels = 0;
  InteriorGuardStats interior_guard;
  CoarsePlatesStats coarse_plates;
  PostProcessStats post_process;
  HandleRetry handle_retry;
  PieceSeparationStats separation;
  HoleOpeningStats holes;
  GapRefillStats refill;
  double seconds = 0.0;
};

// Called after every generation, on the shrinking thread.
using GenerationCallback = std::function<void(const GenerationStats&)>;

// Shrinks the initial membrane of `grid` (as built by Voxelize from `points`) into the final
// DMS. The points are read by the thin-part exception of the thick-wall incursion test
// (ChainRules::thin_part_min_spread, incursion_test.h) and by the opening of plugged holes
// (ShrinkOptions::holes, hole_opening.h); they are indexed once (12 bytes a point and 12 a
// hard voxel, held during the shrink) when either is on.
// `generations` holds the rows of the generations kept: after a kept handle retry, the retry's
// rows (handle_retry set) replace the first run's from HandleRetry::from_generation on.
// Generations run on a coarser grid (ShrinkOptions::coarse_plates) have rows of their own,
// with their level. `on_generation` sees every first-run row as it finishes, then, when a
// retry is kept, the retry's rows, each replacing the earlier row of the same generation.
// After success the membrane invariants hold (CheckMembraneInvariants) and `grid` holds the
// final DMS. `on_generation` may be empty. Cancelled when `cancel` fires (within
// milliseconds; `grid` is then a valid but unfinished DMS); InvalidArgument for bad options.
absl::StatusOr<ShrinkResult> ShrinkMembrane(VoxelGrid& grid, absl::Span<const Point3f> points,
                                            const ShrinkOptions& options,
                                            const GenerationCallback& on_generation,
                                            const CancelToken& cancel);

// The same without the points: the thin-part exception finds no data on both sides of a run
// and never applies (the thick-wall test fires as with thick_wall_detour 0), and no plugged
// hole is opened.
absl::StatusOr<ShrinkResult> ShrinkMembrane(VoxelGrid& grid, const ShrinkOptions& options,
                                            const GenerationCallback& on_generation,
                                            const CancelToken& cancel);

// The grid's states and their counts at one point of the shrink, the states as runs
// (compact_states.h): a plain copy would hold as many bytes as the grid.
struct ShrinkCheckpoint {
  CompactStates states;
  StateCounts counts;
  bool band_held = false;  // the interior guard's band frozen in `states`
};

// The guard sizes a generation runs with: the grid's (GridGuardSizes) or the handle retry's
// strict ones over them (StrictGuardSizes).
enum class TunnelRules { kDefault, kStrict };

// The state of one shrink, and its steps in the paper's order: Run calls them. It holds the
// grid, the plate sizes and labels of its generations, the state counts after the last one,
// and the work planes, place finder and chain runner every generation reuses.
class MembraneShrinker {
 public:
  // Keeps references to `grid` (as built by Voxelize from `points`), `options` (valid by
  // ValidateShrinkOptions) and `cancel`, which must outlive the shrinker. Takes the plate sizes
  // and labels of the grid's data box (Algorithm 1); allocates no planes yet. Indexes the
  // points when the thin-part exception or the hole opening reads them (ShrinkMembrane).
  MembraneShrinker(VoxelGrid& grid, const ShrinkOptions& options, const CancelToken& cancel,
                   absl::Span<const Point3f> points = {});

  MembraneShrinker(const MembraneShrinker&) = delete;
  MembraneShrinker& operator=(const MembraneShrinker&) = delete;

  // The whole shrink, as ShrinkMembrane states it: the silhouette pre-shrink (when enabled),
  // the interior guard, the leading big plates on a coarser grid where options.coarse_plates
  // applies (coarse_plates.h), every other generation, the handle retry (handle_retry.h), the
  // section 7 post-process.
  absl::StatusOr<ShrinkResult> Run(const GenerationCallback& on_generation);

  // Generation g (0-based) with the guard sizes of `rules`: its closed form where that applies
  // (closed_form_generation.h), otherwise snapshots and chains until a pass changes nothing.
  // Appends the generation's row to `rows`. Under the default rules from the first generation
  // the handle retry may run again, the row counts the removals the strict sizes would refuse.
  // Cancelled when the token fires (the grid is then a valid but unfinished DMS).
  absl::Status RunGeneration(size_t g, TunnelRules rules, std::vector<GenerationStats>& rows);

  // `to` becomes a copy of the grid's states and their counts; the grid's states and counts
  // become `from`. Both poll the token between slices of the copy: false when it fired (the shrink
  // is then abandoned, a half-copied grid with it). `from` must be a copy of this grid.
  bool Save(ShrinkCheckpoint& to) const;
  bool Restore(const ShrinkCheckpoint& from);

  const VoxelGrid& grid() const { return grid_; }
  // The work planes: nothing in them outlives a generation, so a step between generations
  // may use them (the handle retry measures its web on two) instead of allocating planes of
  // its own beside them.
  WorkPlanes& work_planes() { return planes_; }
  const ShrinkOptions& options() const { return options_; }
  const CancelToken& cancel() const { return cancel_; }
  size_t generations() const { return sizes_.size(); }
  int plate_size(size_t g) const { return sizes_[g]; }
  int label(size_t g) const { return labels_[g]; }

  // Counts the grid's states again, as the next generation's row starts from: Run does before
  // the first generation; a caller that runs generations itself, or changes the grid between
  // them, calls it first.
  void Recount();

 private:
  // The chains of generation g under `rules`: plate size, label, rules and guard sizes.
  ChainOptions ChainOptionsFor(size_t g, TunnelRules rules) const;
  // Snapshots of every fitting plate, then a chain from each candidate, until a pass changes
  // nothing; adds to `stats`.
  absl::Status RunChains(const ChainOptions& chain, GenerationStats& stats);

  VoxelGrid& grid_;
  const ShrinkOptions& options_;
  const CancelToken& cancel_;
  const GuardSizes guard_;        // the guard's sizes on this grid (GridGuardSizes)
  const GuardSizes strict_;       // the handle retry's sizes over them
  const std::vector<int> sizes_;  // plate size of each generation
  const std::vector<int> labels_;  // generation label of each generation
  // The first generation whose plate is below the strict tunnel size: from there on the
  // strict sizes differ from the default ones, and the handle retry runs again. sizes_.size()
  // when the retry is off or no plate is that small.
  const size_t retry_from_;
  // Threads of the word passes and state counts: options.threads on grids of at least
  // options.threads_min_voxels voxels, else 1.
  const int word_threads_;
  // The counts after the last generation, before the next: one pass over the states per
  // generation (on a 70 M voxel grid each pass costs as much as a small generation).
  StateCounts counts_;
  GuardedBand guarded_band_;  // the band GuardInteriors froze, released by plate size
  // A generation's closed form was refused by its checks (ShrinkOptions::
  // closed_form_after_refusal).
  bool closed_form_refused_ = false;
  // Made beside the guard on a grid with threaded word passes (PlanesAhead), else at the
  // first snapshot or closed form.
  WorkPlanes planes_;
  PlaceFinder finder_;
  ChainRunner runner_;
  std::optional<HardVoxelPoints> points_;  // when the thin-part exception or holes read them
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_MEMBRANE_SHRINKER_H_

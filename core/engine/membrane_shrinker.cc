#include "core/engine/membrane_shrinker.h"

#include <algorithm>
#include <chrono>
#include <optional>

#include "absl/status/status.h"
#include "absl/strings/str_format.h"
#include "core/engine/closed_form_generation.h"
#include "core/engine/contraction.h"
#include "core/engine/place_finder.h"
#include "core/engine/silhouette.h"
#include "core/engine/state_planes.h"
#include "core/engine/work_planes.h"

namespace membrane {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

absl::Status CancelledIn(const GenerationStats& g) {
  return absl::CancelledError(absl::StrFormat(
      "reconstruction cancelled in generation %d (plate size %d)", g.generation, g.plate_size));
}

// One generation: snapshots of every fitting plate, then a chain from each candidate, until a
// pass changes nothing (then no plate fits anywhere: every plate that fits now but did not at
// the last snapshot contains a voxel that a chain of the pass changed).
absl::Status RunGeneration(VoxelGrid& grid, PlaceFinder& finder, ChainRunner& runner,
                           const ChainOptions& chain, const CancelToken* cancel,
                           GenerationStats& stats) {
  ChainCounters counters;
  for (;;) {
    if (cancel != nullptr && cancel->cancelled()) return CancelledIn(stats);
    const std::optional<std::vector<int64_t>> snapshot = finder.Snapshot(chain.plate_size, cancel);
    if (!snapshot) return CancelledIn(stats);
    const std::vector<int64_t>& candidates = *snapshot;
    ++stats.passes;
    bool changed = false;
    for (int64_t index : candidates) {
      if (grid.at(index) != kBoundarySoft) continue;
      const std::optional<Plate> plate = finder.PlaceFor(index);
      if (!plate) continue;
      const ChainOutcome outcome = runner.Run(*plate, chain, cancel, counters);
      if (outcome == ChainOutcome::kCancelled) return CancelledIn(stats);
      if (outcome == ChainOutcome::kSkipped) continue;
      ++stats.started_contractions;
      if (outcome == ChainOutcome::kBacktracked) ++stats.backtrackings;
      changed = true;
    }
    if (!changed) break;
  }
  stats.contractions = counters.contractions;
  stats.undone_contractions = counters.undone_contractions;
  stats.guard_refusals = counters.guard_refusals;
  stats.depth_refusals = counters.depth_refusals;
  return absl::OkStatus();
}

}  // namespace

absl::Status ValidateShrinkOptions(const ShrinkOptions& o) {
  if (o.initial_plate < 0 || o.initial_plate > 100000) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "initial_plate %d is out of range [0, 100000] (0 = from the grid)", o.initial_plate));
  }
  if (o.depth_bound < 0 || o.depth_bound > 1000000) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "depth_bound %d is out of range [0, 1000000] (0 = unbounded)", o.depth_bound));
  }
  if (o.closed_form_min_plate < 0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "closed_form_min_plate %d must be >= 0 (0 = never)", o.closed_form_min_plate));
  }
  if (o.guard_tunnel_min_plate < 1) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "guard_tunnel_min_plate %d must be >= 1", o.guard_tunnel_min_plate));
  }
  if (o.guard_short_loop_min_plate < 0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "guard_short_loop_min_plate %d must be >= 0 (0 = off)", o.guard_short_loop_min_plate));
  }
  if (o.guard_wall_notch_min_plate < 0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "guard_wall_notch_min_plate %d must be >= 0 (0 = off)", o.guard_wall_notch_min_plate));
  }
  if (o.guard_short_loop_steps < 1 || o.guard_short_loop_steps > 64) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "guard_short_loop_steps %d is out of range [1, 64]", o.guard_short_loop_steps));
  }
  if (o.thick_wall_run < 1 || o.thick_wall_run > 5) {
    return absl::InvalidArgumentError(
        absl::StrFormat("thick_wall_run %d is out of range [1, 5]", o.thick_wall_run));
  }
  return absl::OkStatus();
}

absl::StatusOr<ShrinkResult> ShrinkMembrane(VoxelGrid& grid, const ShrinkOptions& options,
                                            const GenerationCallback& on_generation,
                                            const CancelToken* cancel) {
  if (absl::Status s = ValidateShrinkOptions(options); !s.ok()) return s;
  const Clock::time_point start = Clock::now();
  ShrinkResult result;
  std::array<int, 3> data_dims;
  for (int d = 0; d < 3; ++d) data_dims[d] = grid.dim(d) - 2 * VoxelGrid::kPadding;
  if (options.silhouette_preshrink) result.preshrink_outside_voxels = SilhouettePreshrink(grid);

  const std::vector<int> sizes = PlateSizes(data_dims, options.schedule, options.initial_plate);
  const std::vector<int> labels = GenerationLabels(static_cast<int>(sizes.size()));
  WorkPlanes planes(grid);  // allocated at the first snapshot or closed form
  PlaceFinder finder(grid, planes);
  ChainRunner runner(grid);
  // One pass over the states per generation: the counts after one are the counts before the
  // next (on a 70 M voxel grid each pass costs as much as a small generation).
  StateCounts counts = CountStates(grid.states());
  for (size_t g = 0; g < sizes.size(); ++g) {
    const Clock::time_point t0 = Clock::now();
    GenerationStats stats;
    stats.generation = static_cast<int>(g) + 1;
    stats.plate_size = sizes[g];
    stats.soft_voxels = counts.boundary_soft;
    ChainOptions chain;
    chain.plate_size = sizes[g];
    chain.generation_label = labels[g];
    chain.depth_bound = options.depth_bound;
    chain.depth_bound_max_plate = options.depth_bound_max_plate;
    chain.thick_wall_run = options.thick_wall_run;
    chain.topology_guard = options.topology_guard;
    chain.guard_tunnel_min_plate = options.guard_tunnel_min_plate;
    chain.guard_short_loop_min_plate = options.guard_short_loop_min_plate;
    chain.guard_short_loop_steps = options.guard_short_loop_steps;
    chain.guard_wall_notch_min_plate = options.guard_wall_notch_min_plate;
    bool done = false;
    // The closed form needs the chains' tunnel rule to be the same everywhere (n >= the guard's
    // tunnel size): then only tunnels next to hard voxels are refused, and it checks those.
    if (options.closed_form_min_plate > 0 && sizes[g] >= options.closed_form_min_plate &&
        sizes[g] >= options.guard_tunnel_min_plate) {
      absl::StatusOr<ClosedFormOutcome> closed =
          RunClosedFormGeneration(grid, chain, cancel, planes);
      if (!closed.ok()) return CancelledIn(stats);
      done = stats.closed_form = closed->applied;
      stats.closed_form_rounds = closed->rounds;
      stats.closed_form_checks = closed->checks;
    }
    if (!done) {
      if (absl::Status s = RunGeneration(grid, finder, runner, chain, cancel, stats); !s.ok()) {
        return s;
      }
    }
    const StateCounts after = CountStates(grid.states());
    stats.new_outside = after.outside - counts.outside;
    counts = after;
    stats.seconds = SecondsSince(t0);
    result.generations.push_back(stats);
    if (on_generation) on_generation(stats);
  }
  if (options.connect_inside_hard) {
    absl::StatusOr<PostProcessStats> post = ConnectInsideHardVoxels(grid, cancel);
    if (!post.ok()) return post.status();
    result.post_process = *post;
  }
  result.seconds = SecondsSince(start);
  return result;
}

}  // namespace membrane

#include "core/engine/membrane_shrinker.h"

#include <algorithm>
#include <chrono>
#include <numeric>
#include <optional>

#include "absl/status/status.h"
#include "absl/strings/str_format.h"
#include "core/engine/closed_form_generation.h"
#include "core/engine/contraction.h"
#include "core/engine/huge_page_allocator.h"
#include "core/engine/place_finder.h"
#include "core/engine/silhouette.h"
#include "core/engine/state_planes.h"
#include "core/engine/voxel_topology.h"
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
                           const ChainOptions& chain, const CancelToken& cancel,
                           GenerationStats& stats) {
  ChainCounters counters;
  for (;;) {
    if (cancel.cancelled()) return CancelledIn(stats);
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
  stats.loose_tunnels = counters.loose_tunnels;
  return absl::OkStatus();
}

// The guard's tunnel rules of the retry: tunnels away from the data only from the larger plate
// size, short-loop tunnels only from the larger size (still off when off).
ShrinkOptions StrictTunnelRules(const ShrinkOptions& o) {
  ShrinkOptions strict = o;
  strict.guard_tunnel_min_plate = std::max(o.guard_tunnel_min_plate, o.retry_tunnel_min_plate);
  if (o.guard_short_loop_min_plate > 0) {
    strict.guard_short_loop_min_plate =
        std::max(o.guard_short_loop_min_plate, o.retry_short_loop_min_plate);
  }
  return strict;
}

// Copies of the whole grid's states: on huge pages, since a 70 M voxel copy would otherwise
// spend longer in 4 KB page faults than in copying.
using StateCopy = std::vector<VoxelState, HugePageAllocator<VoxelState>>;

// What the retry closed: the voxels outside in `first` that are solid in `grid` (the web), and
// the share of hard voxels among the voxels solid in both that touch them (its rim). A web
// across missing data hangs on frozen and soft voxels; a membrane across a real hole of a
// scanned object hangs on the hole's scanned edge (a torus 2.25-2.75x the formula-(1) size:
// 89-94% hard; the spot scan's webs between its legs: 7%).
void MeasureWeb(const VoxelGrid& grid, const StateCopy& first, HandleRetry& r) {
  const VoxelState* now = grid.states().data();
  std::vector<char> counted;
  int64_t rim = 0, hard = 0;
  auto is_web = [&](int64_t i) { return IsOutside(first[i]) && !IsOutside(now[i]); };
  for (int z = 1; z + 1 < grid.dim(2); ++z)
    for (int y = 1; y + 1 < grid.dim(1); ++y)
      for (int x = 1; x + 1 < grid.dim(0); ++x) {
        const int64_t i = grid.Index(x, y, z);
        if (!is_web(i)) continue;
        ++r.web_voxels;
        if (counted.empty()) counted.assign(first.size(), 0);
        for (int64_t offset : grid.block_offsets()) {
          const int64_t j = i + offset;
          if (counted[j] || IsOutside(now[j]) || is_web(j)) continue;
          counted[j] = 1;
          ++rim;
          hard += IsHard(now[j]);
        }
      }
  r.web_hard_rim = rim > 0 ? static_cast<double>(hard) / rim : 0.0;
}

// Calls copy(begin, end) for consecutive slices of [0, count), 16 MB each (a few milliseconds),
// polling `cancel` between them: a 70 M voxel copy takes about 0.1 s, the whole cancellation
// budget. False when cancelled (the reconstruction is then abandoned, half-copied states with
// it).
template <typename CopySlice>
bool CopyInSlices(size_t count, const CancelToken& cancel, CopySlice copy) {
  constexpr size_t kSlice = size_t{16} << 20;
  for (size_t begin = 0; begin < count; begin += kSlice) {
    if (cancel.cancelled()) return false;
    copy(begin, std::min(count, begin + kSlice));
  }
  return true;
}

// `to` becomes a copy of the grid's states (appended slice by slice: no zero fill first).
bool CopyStates(const VoxelGrid& grid, StateCopy& to, const CancelToken& cancel) {
  const VoxelState* from = grid.states().data();
  to.clear();
  to.reserve(grid.states().size());
  return CopyInSlices(grid.states().size(), cancel, [&](size_t begin, size_t end) {
    to.insert(to.end(), from + begin, from + end);
  });
}

// The grid's states become `from`.
bool CopyStates(const StateCopy& from, VoxelGrid& grid, const CancelToken& cancel) {
  VoxelState* to = grid.mutable_states().data();
  return CopyInSlices(from.size(), cancel, [&](size_t begin, size_t end) {
    std::copy(from.begin() + begin, from.begin() + end, to + begin);
  });
}

absl::Status RetryCancelled() {
  return absl::CancelledError("reconstruction cancelled in the handle retry");
}

// ComputeVoxelTopology, polling `cancel` between its passes.
absl::StatusOr<VoxelTopology> Topology(const VoxelGrid& grid, const CancelToken& cancel) {
  std::optional<VoxelTopology> topology = ComputeVoxelTopology(grid, cancel);
  if (!topology) return RetryCancelled();
  return *std::move(topology);
}

int TotalGenus(const VoxelTopology& t) {
  return std::accumulate(t.genus.begin(), t.genus.end(), 0);
}

// The handle retry (docs/engine-decisions.md): when the finished generations left handles,
// runs generations [from, to) again from `before` with the strict rules and keeps whichever
// result has fewer handles without fewer shells. The tunnels that mitosis needs close again
// before the end (two spheres: genus 0 either way), so only handles that survive are weighed.
template <typename RunGenerationFn>
absl::Status RetryHandles(VoxelGrid& grid, const StateCopy& before, double max_hard_rim,
                          const StateCounts& counts_before, size_t from, size_t to,
                          RunGenerationFn& run_generation,
                          const GenerationCallback& on_generation, const CancelToken& cancel,
                          StateCounts& counts, ShrinkResult& result) {
  const Clock::time_point t0 = Clock::now();
  HandleRetry& r = result.handle_retry;
  r.from_generation = static_cast<int>(from) + 1;
  for (size_t g = from; g < to; ++g) r.loose_tunnels += result.generations[g].loose_tunnels;
  // Without a removal the strict rules refuse, they would make every decision the same.
  if (r.loose_tunnels == 0) return absl::OkStatus();
  absl::StatusOr<VoxelTopology> topology = Topology(grid, cancel);
  if (!topology.ok()) return topology.status();
  const VoxelTopology first = *std::move(topology);
  r.shells_before = r.shells_after = first.shells;
  r.genus_before = r.genus_after = TotalGenus(first);
  if (r.genus_before > 0) {
    r.ran = true;
    StateCopy finished;
    if (!CopyStates(grid, finished, cancel) ||
        !CopyStates(before, grid, cancel))
      return RetryCancelled();
    const StateCounts counts_finished = counts;
    counts = counts_before;
    std::vector<GenerationStats> rows;
    for (size_t g = from; g < to; ++g)
      if (absl::Status s = run_generation(g, /*strict_run=*/true, rows); !s.ok()) return s;
    topology = Topology(grid, cancel);
    if (!topology.ok()) return topology.status();
    const VoxelTopology second = *std::move(topology);
    r.kept = second.shells >= first.shells && TotalGenus(second) < r.genus_before;
    if (r.kept) {
      MeasureWeb(grid, finished, r);
      r.kept = r.web_hard_rim < max_hard_rim;
    }
    if (r.kept) {
      r.shells_after = second.shells;
      r.genus_after = TotalGenus(second);
      for (GenerationStats& row : rows) row.handle_retry = true;
      std::copy(rows.begin(), rows.end(), result.generations.begin() + from);
      // Reported once kept: a row that is thrown away would only confuse a progress display.
      if (on_generation)
        for (const GenerationStats& row : rows) on_generation(row);
    } else {
      if (!CopyStates(finished, grid, cancel)) return RetryCancelled();
      counts = counts_finished;
    }
  }
  r.seconds = SecondsSince(t0);
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
  if (o.retry_tunnel_min_plate < 1) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "retry_tunnel_min_plate %d must be >= 1", o.retry_tunnel_min_plate));
  }
  if (o.retry_short_loop_min_plate < 0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "retry_short_loop_min_plate %d must be >= 0", o.retry_short_loop_min_plate));
  }
  if (!(o.retry_max_hard_rim >= 0)) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "retry_max_hard_rim %g must be >= 0", o.retry_max_hard_rim));
  }
  if (o.thick_wall_run < 1 || o.thick_wall_run > 5) {
    return absl::InvalidArgumentError(
        absl::StrFormat("thick_wall_run %d is out of range [1, 5]", o.thick_wall_run));
  }
  return absl::OkStatus();
}

absl::StatusOr<ShrinkResult> ShrinkMembrane(VoxelGrid& grid, const ShrinkOptions& options,
                                            const GenerationCallback& on_generation,
                                            const CancelToken& cancel) {
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
  // The strict rules differ from the default ones from the first generation whose plate is
  // below their tunnel size: the grid is kept as it was before it, for the retry.
  const ShrinkOptions strict = StrictTunnelRules(options);
  size_t retry_from = sizes.size();
  if (options.retry_handles) {
    for (size_t g = 0; g < sizes.size() && retry_from == sizes.size(); ++g)
      if (sizes[g] < strict.guard_tunnel_min_plate) retry_from = g;
  }
  // Generation g with the default or the strict tunnel rules; appends its row to `rows`. From
  // retry_from on, the default run counts the removals the strict rules would refuse.
  auto run_generation = [&](size_t g, bool strict_run,
                            std::vector<GenerationStats>& rows) -> absl::Status {
    const ShrinkOptions& rules = strict_run ? strict : options;
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
    chain.guard_tunnel_min_plate = rules.guard_tunnel_min_plate;
    chain.guard_short_loop_min_plate = rules.guard_short_loop_min_plate;
    chain.guard_short_loop_steps = options.guard_short_loop_steps;
    chain.guard_wall_notch_min_plate = options.guard_wall_notch_min_plate;
    chain.classify_strict = g >= retry_from && !strict_run;
    chain.strict_tunnel_min_plate = strict.guard_tunnel_min_plate;
    chain.strict_short_loop_min_plate = strict.guard_short_loop_min_plate;
    bool done = false;
    // The closed form needs the chains' tunnel rule to be the same everywhere (n >= the guard's
    // tunnel size): then only tunnels next to hard voxels are refused, and it checks those.
    if (options.closed_form_min_plate > 0 && sizes[g] >= options.closed_form_min_plate &&
        sizes[g] >= rules.guard_tunnel_min_plate) {
      absl::StatusOr<ClosedFormOutcome> closed =
          RunClosedFormGeneration(grid, chain, cancel, planes);
      if (!closed.ok()) return CancelledIn(stats);
      done = stats.closed_form = closed->applied;
      stats.closed_form_rounds = closed->rounds;
      stats.closed_form_checks = closed->checks;
      // It allows every tunnel away from hard voxels: the strict rules might not have.
      if (done && chain.classify_strict && sizes[g] < strict.guard_tunnel_min_plate)
        stats.loose_tunnels = 1;
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
    rows.push_back(stats);
    return absl::OkStatus();
  };

  StateCopy before_retry;
  StateCounts counts_before_retry;
  for (size_t g = 0; g < sizes.size(); ++g) {
    if (g == retry_from) {
      if (!CopyStates(grid, before_retry, cancel)) {
        return RetryCancelled();
      }
      counts_before_retry = counts;
    }
    if (absl::Status s = run_generation(g, /*strict_run=*/false, result.generations); !s.ok()) {
      return s;
    }
    if (on_generation) on_generation(result.generations.back());
  }
  if (retry_from < sizes.size()) {
    if (absl::Status s = RetryHandles(grid, before_retry, options.retry_max_hard_rim,
                                      counts_before_retry, retry_from,
                                      sizes.size(), run_generation, on_generation, cancel,
                                      counts, result);
        !s.ok()) {
      return s;
    }
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

#include "core/engine/membrane_shrinker.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <optional>

#include "absl/status/status.h"
#include "absl/strings/str_format.h"
#include "absl/types/span.h"
#include "core/engine/closed_form_generation.h"
#include "core/engine/coarse_plates.h"
#include "core/engine/gap_refill.h"
#include "core/engine/hole_opening.h"
#include "core/engine/handle_retry.h"
#include "core/engine/interior_guard.h"
#include "core/engine/planes_ahead.h"
#include "core/engine/plate_schedule.h"
#include "core/engine/silhouette.h"

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

// The grid's data box: the grid without its padding.
std::array<int, 3> DataDims(const VoxelGrid& grid) {
  std::array<int, 3> data_dims;
  for (int d = 0; d < 3; ++d) data_dims[d] = grid.dim(d) - 2 * VoxelGrid::kPadding;
  return data_dims;
}

// The first generation whose plate is below the strict tunnel size; sizes.size() when none
// is or the retry is off.
size_t RetryFrom(const std::vector<int>& sizes, const ShrinkOptions& options,
                 const GuardSizes& strict) {
  if (!options.retry.enabled) return sizes.size();
  for (size_t g = 0; g < sizes.size(); ++g)
    if (sizes[g] < strict.tunnel_min_plate) return g;
  return sizes.size();
}

}  // namespace

MembraneShrinker::MembraneShrinker(VoxelGrid& grid, const ShrinkOptions& options,
                                   const CancelToken& cancel, absl::Span<const Point3f> points)
    : grid_(grid),
      options_(options),
      cancel_(cancel),
      guard_(GridGuardSizes(options, DataDims(grid))),
      strict_(StrictGuardSizes(options, guard_)),
      sizes_(PlateSizes(DataDims(grid), options.schedule, options.initial_plate)),
      labels_(GenerationLabels(static_cast<int>(sizes_.size()))),
      retry_from_(RetryFrom(sizes_, options, strict_)),
      word_threads_(grid.size() >= options.threads_min_voxels ? options.threads : 1),
      planes_(grid, word_threads_),
      finder_(grid, planes_),
      runner_(grid) {
  // Only the thin-part exception, the piece separation's split and the hole opening read the
  // points.
  const bool thin_parts =
      options.chain.thick_wall_run > 1 &&
      ((options.chain.thick_wall_detour > 0 && options.chain.thin_part_min_spread > 0) ||
       options.chain.thin_wall_face_gap > 0);
  const bool split = options.separation.enabled && options.separation.split_reach > 0;
  if ((thin_parts || split || options.holes.enabled) && !points.empty()) {
    points_.emplace(grid, points, word_threads_);
  }
}

absl::StatusOr<ShrinkResult> MembraneShrinker::Run(const GenerationCallback& on_generation) {
  const Clock::time_point start = Clock::now();
  ShrinkResult result;
  result.guard = guard_;
  if (options_.silhouette_preshrink) result.preshrink_outside_voxels = SilhouettePreshrink(grid_);
  // On a grid big enough for the word passes' threads, the planes' first writes run beside the
  // guard and the coarse plates, which use none of them (planes_ahead.h).
  std::optional<PlanesAhead> ahead;
  if (word_threads_ > 1) ahead.emplace(planes_, WorkPlanes::kArenaPlanes, cancel_);
  {
    absl::StatusOr<InteriorGuardStats> guard =
        GuardInteriors(grid_, options_, cancel_, &guarded_band_);
    if (!guard.ok()) return guard.status();
    result.interior_guard = *guard;
  }
  // The big plates on the coarser grid: the grid's generations go on after them.
  size_t first = 0;
  if (const size_t count = CoarseGenerationCount(grid_.size(), sizes_, options_, retry_from_);
      count > 0) {
    absl::StatusOr<CoarsePlatesStats> coarse = RunCoarsePlates(
        grid_, options_, sizes_, labels_, count, cancel_, on_generation, result.generations);
    if (!coarse.ok()) return coarse.status();
    result.coarse_plates = *coarse;
    first = static_cast<size_t>(coarse->generations);
  }
  ahead.reset();  // the planes are the generations' again
  Recount();
  // The strict rules decide as the default ones do until the first removal they would refuse
  // (a loose tunnel): the handle retry starts at the generation that made it, from the grid
  // as it was before that generation.
  ShrinkCheckpoint retry_start;  // the grid before generation retry_at
  size_t retry_at = retry_from_;
  bool loose = false;
  for (size_t g = first; g < sizes_.size(); ++g) {
    if (g >= retry_from_ && !loose) {
      if (!Save(retry_start)) return HandleRetryCancelled();
      retry_at = g;
    }
    if (absl::Status s = RunGeneration(g, TunnelRules::kDefault, result.generations); !s.ok()) {
      return s;
    }
    loose = loose || (g >= retry_from_ && result.generations.back().loose_tunnels > 0);
    if (on_generation) on_generation(result.generations.back());
  }
  if (retry_from_ < sizes_.size()) {
    if (absl::Status s = RetryHandles(*this, retry_start, retry_at, on_generation, result);
        !s.ok()) {
      return s;
    }
  }
  if (result.interior_guard.frozen_voxels > 0) {
    result.interior_guard.released_voxels = ReleaseInteriorGuard(grid_, word_threads_);
  }
  // The steps after the generations take no work planes (the piece separation holds a byte
  // a voxel of its own): the planes' bytes, as many as the grid's, go back first.
  finder_.Release();
  planes_.Release();
  {
    absl::StatusOr<PieceSeparationStats> separation =
        SeparateDataPieces(grid_, options_.separation, cancel_, points_ ? &*points_ : nullptr);
    if (!separation.ok()) return separation.status();
    result.separation = *separation;
  }
  {
    absl::StatusOr<HoleOpeningStats> holes =
        OpenPluggedHoles(grid_, options_.holes, points_ ? &*points_ : nullptr, cancel_,
                         word_threads_);
    if (!holes.ok()) return holes.status();
    result.holes = *holes;
  }
  // A separation can need a real hole the shrink left plugged (a ring's plugged hole facing
  // another object): cutting the webs around it opens the hole as well, one handle more than
  // the joined shell had, and the trials are refused. Once the hole opening has opened such
  // holes from their data, a separation that passed the size test but not the topology test
  // is tried again on the grid as it now is.
  if (!result.separation.separated && result.separation.shells_after > 0 &&
      result.separation.cut_fraction <= options_.separation.max_cut_fraction &&
      result.holes.opened > 0) {
    absl::StatusOr<PieceSeparationStats> again =
        SeparateDataPieces(grid_, options_.separation, cancel_, points_ ? &*points_ : nullptr);
    if (!again.ok()) return again.status();
    if (again->separated) {
      again->seconds += result.separation.seconds;
      result.separation = *again;
    } else {
      result.separation.seconds += again->seconds;
    }
  }
  {
    const Clock::time_point t = Clock::now();
    absl::StatusOr<GapRefillStats> refill =
        RefillGapChannels(grid_, options_.refill, cancel_, word_threads_);
    if (!refill.ok()) return refill.status();
    result.refill = *refill;
    result.refill.seconds = SecondsSince(t);
  }
  if (options_.connect_inside_hard) {
    const Clock::time_point t = Clock::now();
    absl::StatusOr<PostProcessStats> post =
        ConnectInsideHardVoxels(grid_, cancel_, /*max_path=*/64, word_threads_);
    if (!post.ok()) return post.status();
    result.post_process = *post;
    result.post_process.seconds = SecondsSince(t);
  }
  result.seconds = SecondsSince(start);
  return result;
}

void MembraneShrinker::Recount() { counts_ = CountStates(grid_.states(), word_threads_); }

ChainOptions MembraneShrinker::ChainOptionsFor(size_t g, TunnelRules rules) const {
  ChainOptions chain;
  chain.generation_label = labels_[g];
  chain.rules = options_.chain;
  chain.guard.plate_size = sizes_[g];
  chain.guard.sizes = rules == TunnelRules::kStrict ? strict_ : guard_;
  chain.guard.classify_strict = rules == TunnelRules::kDefault && g >= retry_from_;
  chain.guard.strict = strict_;
  chain.points = points_ ? &*points_ : nullptr;
  return chain;
}

absl::Status MembraneShrinker::RunGeneration(size_t g, TunnelRules rules,
                                             std::vector<GenerationStats>& rows) {
  const Clock::time_point t0 = Clock::now();
  if (guarded_band_.held && sizes_[g] < options_.interior_guard.band_release_below) {
    ReleaseGuardedBand(grid_, guarded_band_, word_threads_);
  }
  GenerationStats stats;
  stats.generation = static_cast<int>(g) + 1;
  stats.plate_size = sizes_[g];
  stats.soft_voxels = counts_.boundary_soft;
  const ChainOptions chain = ChainOptionsFor(g, rules);
  bool done = false;
  // The closed form needs the chains' tunnel rule to be the same everywhere (n >= the guard's
  // tunnel size): then only tunnels next to hard voxels are refused, and it checks those (and
  // below the object's tunnel plate every new outside voxel: tunnels away from the data then
  // need data around them).
  if (options_.closed_form_min_plate > 0 && sizes_[g] >= options_.closed_form_min_plate &&
      sizes_[g] >= chain.guard.sizes.tunnel_min_plate &&
      (options_.closed_form_after_refusal || !closed_form_refused_)) {
    const int64_t voxelwise_max = options_.closed_form_voxelwise_ratio > 0
                                      ? grid_.size() / options_.closed_form_voxelwise_ratio
                                      : -1;
    absl::StatusOr<ClosedFormOutcome> closed =
        RunClosedFormGeneration(grid_, chain, voxelwise_max, cancel_, planes_);
    if (!closed.ok()) return CancelledIn(stats);
    done = stats.closed_form = closed->applied;
    closed_form_refused_ = closed_form_refused_ || !closed->applied;
    stats.closed_form_rounds = closed->rounds;
    stats.closed_form_checks = closed->checks;
    stats.closed_form_voxelwise = closed->voxelwise;
    // It allows every tunnel away from hard voxels: the strict rules might not have.
    if (done && chain.guard.classify_strict && sizes_[g] < strict_.tunnel_min_plate)
      stats.loose_tunnels = 1;
  }
  if (!done) {
    if (absl::Status s = RunChains(chain, stats); !s.ok()) return s;
  }
  const StateCounts after = CountStates(grid_.states(), word_threads_);
  stats.new_outside = after.outside - counts_.outside;
  counts_ = after;
  stats.seconds = SecondsSince(t0);
  rows.push_back(stats);
  return absl::OkStatus();
}

// A pass ends when no plate fits anywhere: every plate that fits now but did not at the last
// snapshot contains a voxel that a chain of the pass changed.
absl::Status MembraneShrinker::RunChains(const ChainOptions& chain, GenerationStats& stats) {
  ChainCounters counters;
  // The boxes the last pass's chains wrote: the next pass's snapshot is taken near them.
  std::vector<VoxelBox> written;
  for (bool first = true;; first = false) {
    if (cancel_.cancelled()) return CancelledIn(stats);
    const std::optional<std::vector<int64_t>> snapshot =
        first ? finder_.Snapshot(chain.plate_size(), cancel_)
              : finder_.SnapshotAfter(chain.plate_size(), written,
                                      options_.local_snapshots, cancel_);
    if (!snapshot) return CancelledIn(stats);
    const std::vector<int64_t>& candidates = *snapshot;
    ++stats.passes;
    if (finder_.local()) ++stats.local_passes;
    written.clear();
    bool changed = false;
    for (int64_t index : candidates) {
      if (grid_.at(index) != kBoundarySoft) continue;
      const std::optional<Plate> plate = finder_.PlaceFor(index);
      if (!plate) continue;
      const ChainOutcome outcome = runner_.Run(*plate, chain, cancel_, counters);
      if (outcome == ChainOutcome::kCancelled) return CancelledIn(stats);
      if (outcome == ChainOutcome::kSkipped) continue;
      ++stats.started_contractions;
      if (outcome == ChainOutcome::kBacktracked) ++stats.backtrackings;
      changed = true;
      written.insert(written.end(), runner_.last_written().begin(),
                     runner_.last_written().end());
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

bool MembraneShrinker::Save(ShrinkCheckpoint& to) const {
  to.counts = counts_;
  to.band_held = guarded_band_.held;
  return to.states.Encode(grid_.states(), cancel_, word_threads_);
}

bool MembraneShrinker::Restore(const ShrinkCheckpoint& from) {
  if (!from.states.Decode(absl::MakeSpan(grid_.mutable_states()), cancel_, word_threads_)) {
    return false;
  }
  counts_ = from.counts;
  guarded_band_.held = from.band_held;
  return true;
}

absl::StatusOr<ShrinkResult> ShrinkMembrane(VoxelGrid& grid, absl::Span<const Point3f> points,
                                            const ShrinkOptions& options,
                                            const GenerationCallback& on_generation,
                                            const CancelToken& cancel) {
  if (absl::Status s = ValidateShrinkOptions(options); !s.ok()) return s;
  return MembraneShrinker(grid, options, cancel, points).Run(on_generation);
}

absl::StatusOr<ShrinkResult> ShrinkMembrane(VoxelGrid& grid, const ShrinkOptions& options,
                                            const GenerationCallback& on_generation,
                                            const CancelToken& cancel) {
  return ShrinkMembrane(grid, {}, options, on_generation, cancel);
}

}  // namespace membrane

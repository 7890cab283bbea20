#include "core/engine/handle_retry.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"
#include "core/engine/flat_bitset.h"
#include "core/engine/voxel_topology.h"
#include "core/engine/work_planes.h"

namespace membrane {
namespace {

using Clock = std::chrono::steady_clock;

// ComputeVoxelTopology, polling `cancel` between its passes.
absl::StatusOr<VoxelTopology> Topology(const VoxelGrid& grid, const CancelToken& cancel) {
  std::optional<VoxelTopology> topology = ComputeVoxelTopology(grid, cancel);
  if (!topology) return HandleRetryCancelled();
  return *std::move(topology);
}

// What the retry closed: the voxels outside in `first` that are solid in `grid` (the web), and
// the share of hard voxels among the voxels solid in both that touch them (its rim). A web
// across missing data hangs on frozen and soft voxels; a membrane across a real hole of a
// scanned object hangs on the hole's scanned edge (a torus 2.25-2.75x the formula-(1) size:
// 89-94% hard; the spot scan's webs between its legs: 7%). `first_outside` and `counted` are
// planes of the grid's size whose contents are not needed (two work planes): bit-planes, not
// byte arrays, and not planes of their own, which on a 2e9-voxel grid would add 512 MB to the
// shrink's peak (the grid and the work planes are still held here).
void MeasureWeb(const VoxelGrid& grid, const ShrinkCheckpoint& first_run,
                FlatBitset& first_outside, FlatBitset& counted, HandleRetry& r) {
  first_run.states.OutsidePlane(first_outside);
  counted.clear_all();
  const VoxelState* now = grid.states().data();
  int64_t rim = 0, hard = 0;
  auto is_web = [&](int64_t i) { return first_outside.test(i) && !IsOutside(now[i]); };
  for (int z = 1; z + 1 < grid.dim(2); ++z)
    for (int y = 1; y + 1 < grid.dim(1); ++y)
      for (int x = 1; x + 1 < grid.dim(0); ++x) {
        const int64_t i = grid.Index(x, y, z);
        if (!is_web(i)) continue;
        ++r.web_voxels;
        for (int64_t offset : grid.block_offsets()) {
          const int64_t j = i + offset;
          if (counted.test(j) || IsOutside(now[j]) || is_web(j)) continue;
          counted.set(j);
          ++rim;
          hard += IsHard(now[j]);
        }
      }
  r.web_hard_rim = rim > 0 ? static_cast<double>(hard) / rim : 0.0;
}

}  // namespace

absl::Status HandleRetryCancelled() {
  return absl::CancelledError("reconstruction cancelled in the handle retry");
}

absl::Status RetryHandles(MembraneShrinker& shrinker, const ShrinkCheckpoint& start,
                          size_t from, const GenerationCallback& on_generation,
                          ShrinkResult& result) {
  const Clock::time_point t0 = Clock::now();
  const size_t to = shrinker.generations();
  HandleRetry& r = result.handle_retry;
  r.from_generation = static_cast<int>(from) + 1;
  for (size_t g = from; g < to; ++g) r.loose_tunnels += result.generations[g].loose_tunnels;
  // Without a removal the strict rules refuse, they would make every decision the same.
  if (r.loose_tunnels == 0) return absl::OkStatus();
  absl::StatusOr<VoxelTopology> topology = Topology(shrinker.grid(), shrinker.cancel());
  if (!topology.ok()) return topology.status();
  const VoxelTopology first = *std::move(topology);
  r.shells_before = r.shells_after = first.shells;
  r.genus_before = r.genus_after = TotalGenus(first);
  if (r.genus_before > 0) {
    r.ran = true;
    ShrinkCheckpoint finished;
    if (!shrinker.Save(finished) || !shrinker.Restore(start)) return HandleRetryCancelled();
    std::vector<GenerationStats> rows;
    for (size_t g = from; g < to; ++g) {
      if (absl::Status s = shrinker.RunGeneration(g, TunnelRules::kStrict, rows); !s.ok()) {
        return s;
      }
    }
    topology = Topology(shrinker.grid(), shrinker.cancel());
    if (!topology.ok()) return topology.status();
    const VoxelTopology second = *std::move(topology);
    r.kept = second.shells >= first.shells && TotalGenus(second) < r.genus_before;
    if (r.kept) {
      WorkPlanes& planes = shrinker.work_planes();
      if (!planes.Ensure(2, shrinker.cancel())) return HandleRetryCancelled();
      MeasureWeb(shrinker.grid(), finished, planes.plane(0), planes.plane(1), r);
      r.kept = r.web_hard_rim < shrinker.options().retry.max_hard_rim;
    }
    if (r.kept) {
      r.shells_after = second.shells;
      r.genus_after = TotalGenus(second);
      for (GenerationStats& row : rows) row.handle_retry = true;
      std::copy(rows.begin(), rows.end(), result.generations.begin() + from);
      // Reported once kept: a row that is thrown away would only confuse a progress display.
      if (on_generation)
        for (const GenerationStats& row : rows) on_generation(row);
    } else if (!shrinker.Restore(finished)) {
      return HandleRetryCancelled();
    }
  }
  r.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return absl::OkStatus();
}

}  // namespace membrane

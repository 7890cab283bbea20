#include "core/engine/coarse_plates.h"

#include <algorithm>
#include <array>

#include "absl/status/statusor.h"
#include "absl/strings/str_format.h"
#include "core/base/parallel_tasks.h"
#include "core/engine/coarse_grid.h"
#include "core/engine/plate_schedule.h"

namespace membrane {
namespace {

constexpr int kPad = VoxelGrid::kPadding;

// The fine z planes of coarse z plane cz: [first, second).
std::pair<int, int> FinePlanes(const VoxelGrid& grid, int k, int cz) {
  const int z0 = kPad + (cz - kPad) * k;
  return {z0, std::min(z0 + k, grid.dim(2) - kPad)};
}

}  // namespace

size_t CoarseGenerationCount(int64_t grid_voxels, absl::Span<const int> sizes,
                             const ShrinkOptions& options, size_t limit) {
  const CoarsePlatesOptions& o = options.coarse_plates;
  if (o.min_voxels == 0 || grid_voxels < o.min_voxels) return 0;
  if (options.schedule != PlateSchedule::kHalving || options.silhouette_preshrink) return 0;
  const int min_plate = std::max(o.min_plate, options.interior_guard.band_release_below);
  size_t count = 0;
  while (count < std::min(limit, sizes.size()) && sizes[count] >= min_plate) ++count;
  return count;
}

absl::StatusOr<int64_t> RunCoarsePlates(VoxelGrid& grid, const ShrinkOptions& options,
                                        absl::Span<const int> sizes,
                                        absl::Span<const int> labels, size_t count,
                                        const CancelToken& cancel,
                                        const GenerationCallback& on_generation,
                                        std::vector<GenerationStats>& rows) {
  if (count == 0) return 0;
  const int k = options.coarse_plates.factor;
  const int threads =
      grid.size() >= options.threads_min_voxels ? std::max(options.threads, 1) : 1;
  VoxelGrid coarse = CoarseGrid(grid, k, threads);
  // The interior guard has frozen the grid's interior already; the retry starts later than
  // these generations; the coarse grid is under the threshold, so it does not recurse.
  ShrinkOptions coarse_options = options;
  coarse_options.initial_plate = (sizes[0] + k - 1) / k;
  coarse_options.interior_guard.enabled = false;
  coarse_options.retry.enabled = false;
  coarse_options.silhouette_preshrink = false;
  coarse_options.coarse_plates.min_voxels = 0;
  MembraneShrinker shrinker(coarse, coarse_options, cancel);
  if (shrinker.generations() < count) {
    return absl::InternalError(absl::StrFormat(
        "the coarse grid has %d generations, fewer than the %d to run there",
        shrinker.generations(), count));
  }
  std::array<int, kMaxGenerationLabel + 1> fine_labels{};
  shrinker.Recount();
  for (size_t g = 0; g < count; ++g) {
    // Halving commutes with the division: ceil(ceil(n / 2) / k) = ceil(ceil(n / k) / 2).
    if (shrinker.plate_size(g) != (sizes[g] + k - 1) / k) {
      return absl::InternalError(absl::StrFormat(
          "coarse generation %d has plate %d, not ceil(%d / %d)", g + 1,
          shrinker.plate_size(g), sizes[g], k));
    }
    fine_labels[static_cast<size_t>(shrinker.label(g))] = labels[g];
    if (absl::Status s = shrinker.RunGeneration(g, TunnelRules::kDefault, rows); !s.ok()) {
      return s;
    }
    GenerationStats& row = rows.back();
    row.generation = static_cast<int>(g) + 1;
    row.plate_size = sizes[g];
    row.level = k;
    if (on_generation) on_generation(row);
  }
  if (cancel.cancelled()) return absl::CancelledError("reconstruction cancelled in the lift");
  return LiftCoarseOutside(grid, coarse, k, fine_labels, threads);
}

int64_t LiftCoarseOutside(VoxelGrid& grid, const VoxelGrid& coarse, int k,
                          absl::Span<const int> fine_labels, int threads) {
  const std::array<int, 3>& cd = coarse.dims();
  VoxelState* states = grid.mutable_states().data();
  const VoxelState* coarse_states = coarse.states().data();
  const int planes = cd[2] - 2 * kPad;
  std::vector<int64_t> counts(static_cast<size_t>(std::max(threads, 1)), 0);
  // Each task writes the fine planes of its coarse plane only.
  RunTasks(threads, planes, [&](int worker, int64_t task) {
    const int cz = kPad + static_cast<int>(task);
    const auto [z0, z1] = FinePlanes(grid, k, cz);
    int64_t count = 0;
    for (int z = z0; z < z1; ++z) {
      for (int y = kPad; y < grid.dim(1) - kPad; ++y) {
        const VoxelState* crow = coarse_states + coarse.Index(0, (y - kPad) / k + kPad, cz);
        VoxelState* row = states + grid.Index(0, y, z);
        for (int cx = kPad; cx < cd[0] - kPad; ++cx) {
          const VoxelState c = crow[cx];
          if (!IsOutside(c)) continue;
          const VoxelState out =
              OutsideState(fine_labels[static_cast<size_t>(GenerationLabel(c))]);
          const int x0 = kPad + (cx - kPad) * k, x1 = std::min(x0 + k, grid.dim(0) - kPad);
          std::fill(row + x0, row + x1, out);
          count += x1 - x0;
        }
      }
    }
    counts[static_cast<size_t>(worker)] += count;
  });
  // The new membrane: only fine voxels of coarse boundary voxels can touch a lifted one (a
  // coarse INSIDE voxel has no coarse outside 26-neighbour). A task reads the fine planes next
  // to its own, so the even coarse planes go first, then the odd ones: no task reads a plane
  // another task of its round writes.
  const std::array<int64_t, 26>& around = grid.neighbour_offsets();
  for (int parity = 0; parity < 2; ++parity) {
    RunTasks(threads, (planes + 1 - parity) / 2, [&](int, int64_t task) {
      const int cz = kPad + parity + 2 * static_cast<int>(task);
      const auto [z0, z1] = FinePlanes(grid, k, cz);
      for (int z = z0; z < z1; ++z) {
        for (int y = kPad; y < grid.dim(1) - kPad; ++y) {
          const VoxelState* crow = coarse_states + coarse.Index(0, (y - kPad) / k + kPad, cz);
          for (int cx = kPad; cx < cd[0] - kPad; ++cx) {
            if (!IsBoundary(crow[cx])) continue;
            const int x0 = kPad + (cx - kPad) * k, x1 = std::min(x0 + k, grid.dim(0) - kPad);
            for (int x = x0; x < x1; ++x) {
              const int64_t i = grid.Index(x, y, z);
              if (!IsInside(states[i])) continue;
              for (int64_t offset : around) {
                if (IsOutside(states[i + offset])) {
                  states[i] |= kBoundaryBit;
                  break;
                }
              }
            }
          }
        }
      }
    });
  }
  int64_t total = 0;
  for (int64_t c : counts) total += c;
  return total;
}

}  // namespace membrane

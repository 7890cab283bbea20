#include "core/engine/coarse_plates.h"

#include <algorithm>
#include <array>
#include <chrono>

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

absl::StatusOr<CoarsePlatesStats> RunCoarsePlates(VoxelGrid& grid, const ShrinkOptions& options,
                                                  absl::Span<const int> sizes,
                                                  absl::Span<const int> labels, size_t count,
                                                  const CancelToken& cancel,
                                                  const GenerationCallback& on_generation,
                                                  std::vector<GenerationStats>& rows) {
  const auto start = std::chrono::steady_clock::now();
  CoarsePlatesStats stats;
  if (count == 0) return stats;
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
  stats.factor = k;
  stats.generations = static_cast<int>(count);
  stats.lifted_voxels = LiftCoarseOutside(grid, coarse, k, fine_labels, threads);
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

int64_t LiftCoarseOutside(VoxelGrid& grid, const VoxelGrid& coarse, int k,
                          absl::Span<const int> fine_labels, int threads) {
  const std::array<int, 3>& cd = coarse.dims();
  VoxelState* states = grid.mutable_states().data();
  const VoxelState* coarse_states = coarse.states().data();
  const auto lifted = [&](int64_t c) {
    return IsOutside(coarse_states[c]) && GenerationLabel(coarse_states[c]) > 0;
  };
  std::vector<int64_t> counts(static_cast<size_t>(std::max(threads, 1)), 0);
  // A coarse z plane a task: it writes the fine planes of its coarse plane only, and reads
  // only the coarse grid.
  RunTasks(threads, cd[2] - 2 * kPad, [&](int worker, int64_t task) {
    const int cz = kPad + static_cast<int>(task);
    const auto [z0, z1] = FinePlanes(grid, k, cz);
    const int data_end_x = grid.dim(0) - kPad;
    // A coarse row's lifted voxels as runs of one label: its k x k fine rows take them whole.
    struct Run {
      int x0, x1;
      VoxelState state;
    };
    std::vector<Run> runs;
    int64_t count = 0;
    for (int cy = kPad; cy < cd[1] - kPad; ++cy) {
      runs.clear();
      const int64_t crow = coarse.Index(0, cy, cz);
      for (int cx = kPad; cx < cd[0] - kPad; ++cx) {
        if (!lifted(crow + cx)) continue;
        const VoxelState out =
            OutsideState(fine_labels[static_cast<size_t>(GenerationLabel(coarse_states[crow + cx]))]);
        const int x0 = kPad + (cx - kPad) * k, x1 = std::min(x0 + k, data_end_x);
        if (!runs.empty() && runs.back().x1 == x0 && runs.back().state == out) {
          runs.back().x1 = x1;
        } else {
          runs.push_back({x0, x1, out});
        }
      }
      if (runs.empty()) continue;
      const int y0 = kPad + (cy - kPad) * k, y1 = std::min(y0 + k, grid.dim(1) - kPad);
      for (int z = z0; z < z1; ++z) {
        for (int y = y0; y < y1; ++y) {
          VoxelState* row = states + grid.Index(0, y, z);
          for (const Run& r : runs) {
            std::fill(row + r.x0, row + r.x1, r.state);
            count += r.x1 - r.x0;
          }
        }
      }
    }
    counts[static_cast<size_t>(worker)] += count;
  });
  // The new membrane. A fine voxel of a coarse voxel that was not lifted touches a lifted
  // fine voxel exactly when one of the coarse voxels its 3 x 3 x 3 block reaches was lifted
  // (its own coarse voxel holds no outside voxel; the padding's neighbours are the data
  // region's outer layer, boundary already), and only the fine voxels on a coarse voxel's
  // faces reach its neighbours. So the coarse grid alone says which: a coarse boundary voxel's
  // lifted neighbours as 27 bits, a fine voxel's reachable ones by where it lies in its coarse
  // voxel. Only coarse boundary voxels can have lifted neighbours (a coarse INSIDE voxel has
  // no outside 26-neighbour).
  RunTasks(threads, cd[2] - 2 * kPad, [&](int, int64_t task) {
    const int cz = kPad + static_cast<int>(task);
    for (int cy = kPad; cy < cd[1] - kPad; ++cy) {
      for (int cx = kPad; cx < cd[0] - kPad; ++cx) {
        const int64_t c = coarse.Index(cx, cy, cz);
        if (!IsBoundary(coarse_states[c])) continue;
        uint32_t near = 0;  // bit (dz + 1) * 9 + (dy + 1) * 3 + dx + 1: that neighbour lifted
        for (int b = 0; b < 27; ++b) {
          near |= static_cast<uint32_t>(lifted(c + coarse.block_offsets()[b])) << b;
        }
        if (near == 0) continue;
        const int x0 = kPad + (cx - kPad) * k, y0 = kPad + (cy - kPad) * k,
                  z0 = kPad + (cz - kPad) * k;
        const int x1 = std::min(x0 + k, grid.dim(0) - kPad),
                  y1 = std::min(y0 + k, grid.dim(1) - kPad),
                  z1 = std::min(z0 + k, grid.dim(2) - kPad);
        // The coarse offsets (-1, 0, 1) a fine coordinate's neighbours reach along one axis,
        // as a mask of 3 bits.
        const auto reach = [k](int f, int f0) {
          return 2u | (f == f0 ? 1u : 0u) | (f == f0 + k - 1 ? 4u : 0u);
        };
        for (int z = z0; z < z1; ++z) {
          const uint32_t rz = reach(z, z0);
          for (int y = y0; y < y1; ++y) {
            const uint32_t ry = reach(y, y0);
            VoxelState* row = states + grid.Index(0, y, z);
            for (int x = x0; x < x1; ++x) {
              if (!IsInside(row[x])) continue;
              const uint32_t rx = reach(x, x0);
              bool touches = false;
              for (int dz = 0; dz < 3 && !touches; ++dz) {
                if (!(rz >> dz & 1)) continue;
                for (int dy = 0; dy < 3 && !touches; ++dy) {
                  if (!(ry >> dy & 1)) continue;
                  touches = (near >> (dz * 9 + dy * 3) & rx) != 0;
                }
              }
              if (touches) row[x] |= kBoundaryBit;
            }
          }
        }
      }
    }
  });
  int64_t total = 0;
  for (int64_t c : counts) total += c;
  return total;
}

}  // namespace membrane

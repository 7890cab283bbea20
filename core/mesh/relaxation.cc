#include "core/mesh/relaxation.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "core/base/parallel_tasks.h"
#include "core/engine/local_topology.h"
#include "core/engine/voxel_state_words.h"

namespace membrane {
namespace {

constexpr int kPollSteps = 1024;
// Candidates whose keys one task of the second phase's filter computes.
constexpr int64_t kCandidatesPerTask = int64_t{1} << 12;
constexpr int kPadding = VoxelGrid::kPadding;

// What a voxel adds to its neighbours' DLC.
int Category(VoxelState s) { return IsOutside(s) ? 1 : IsInside(s) ? -1 : 0; }
bool NonOutside(VoxelState s) { return !IsOutside(s); }

// DLC of the voxel whose state `s` points at, from its neighbours at `offsets`.
int SumOfCategories(const VoxelState* s, const std::array<int64_t, 26>& offsets) {
  int dlc = 0;
  for (int64_t o : offsets) dlc += Category(s[o]);
  return dlc;
}

// One bit per boundary voxel among the eight states from `s` on: bit 8k of the result for
// state k (AnyBoundary8's test, kept per byte).
uint64_t BoundaryBits8(const VoxelState* s) {
  const uint64_t w = LoadStates8(s);
  return w & ~(w >> 7) & kLowBits8;
}

// True when one of the 64 states from `s` on is a boundary voxel: a test a cache line, since a
// plane of a large grid is mostly far from the membrane.
bool AnyBoundary64(const VoxelState* s) {
  uint64_t any = 0;
  for (int k = 0; k < 8; ++k) any |= BoundaryBits8(s + 8 * k);
  return any != 0;
}

// Offsets of the nine rows of a 3x3x3 block (dz, dy in -1..1) from its centre's row.
std::array<int64_t, 9> RowOffsets(const VoxelGrid& grid) {
  const std::array<int64_t, 3> st = grid.strides();
  std::array<int64_t, 9> rows{};
  int k = 0;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy) rows[k++] = dz * st[2] + dy * st[1];
  return rows;
}

class Relaxer {
 public:
  Relaxer(VoxelGrid& grid, int threshold, int threads, const CancelToken& cancel,
          ProgressRange progress)
      : grid_(grid),
        threshold_(threshold),
        threads_(threads),
        cancel_(cancel),
        progress_(progress),
        offsets_(grid.neighbour_offsets()),
        row_offsets_(RowOffsets(grid)) {}

  // sign = -1: phase 1 (DLC <= -threshold); +1: phase 2 (DLC >= threshold).
  absl::Status Phase(int sign, RelaxationStats& stats) {
    sign_ = sign;
    // Each phase has half of the progress: its search for the first qualifying voxels, then
    // its steps, half each.
    const ProgressRange phase = sign < 0 ? progress_.Part(0, 0.5) : progress_.Part(0.5, 1);
    const ProgressRange search = phase.Part(0, 0.5), taken = phase.Part(0.5, 1);
    if (cancel_.cancelled()) return Cancel();
    for (auto& b : buckets_) {
      b.items.clear();
      b.next = 0;
    }
    absl::StatusOr<std::vector<int64_t>> first =
        sign < 0 ? ScanGrid(search) : FilterCandidates(search);
    if (!first.ok()) return first.status();
    for (int64_t i : *first) buckets_[Key(i)].items.push_back(i);
    const int64_t first_found = static_cast<int64_t>(first->size());
    std::vector<int64_t>().swap(*first);
    // Every voxel first found is taken once at least; the ones queued again count beyond.
    taken.Begin(first_found);
    int64_t steps = 0, takes = 0;
    for (int key = 26; key >= threshold_;) {
      Bucket& b = buckets_[key];
      if (b.next == b.items.size()) {
        --key;
        continue;
      }
      const int64_t v = b.items[b.next++];
      if (++takes % kPollSteps == 0) taken.Add(kPollSteps);
      if (!Movable(v) || Key(v) != key) continue;  // stale entry
      if (++steps % kPollSteps == 0 && cancel_.cancelled()) return Cancel();
      touched_.clear();
      const bool moved = sign < 0 ? StepInward(v, stats) : StepOutward(v, stats);
      if (!moved) continue;
      for (int64_t t : touched_) Offer(t);
      // A move can raise a neighbour above the current key: restart from the top.
      key = 26;
    }
    taken.Add(takes % kPollSteps);
    return absl::OkStatus();
  }

 private:
  struct Bucket {
    std::vector<int64_t> items;
    size_t next = 0;
  };

  static absl::Status Cancel() { return absl::CancelledError("relaxation cancelled"); }

  // DLC(V), summed from the 26 neighbours' states when asked: a grid-sized array kept up to
  // date would be 1 byte a voxel, and on a 10M-point cloud's 2e9-voxel grid its passes took
  // longer than all the steps (the membrane is 0.2-1% of the voxels). The 3x3x3 block is read
  // as its nine rows of three states, four bytes a load, and counted a byte lane each (at most
  // 9 a lane); the centre's own category is then taken off. `i` must lie in the movable region,
  // so that each load stays within its row.
  int Dlc(int64_t i) const {
    constexpr uint32_t kLow3 = 0x010101;
    const VoxelState* const s = grid_.states().data() + i - 1;
    uint32_t outside = 0, inside = 0;
    for (int64_t row : row_offsets_) {
      uint32_t w;
      std::memcpy(&w, s + row, 4);
      outside += (w >> 7) & kLow3;
      inside += ~(w | (w >> 7)) & kLow3;
    }
    const int block = static_cast<int>((outside * kLow3) >> 16 & 0xff) -
                      static_cast<int>((inside * kLow3) >> 16 & 0xff);
    return block - Category(grid_.at(i));
  }

  int Key(int64_t i) const { return sign_ * Dlc(i); }

  // Phase 1's first qualifying voxels, in index order: each z plane of the movable region
  // lists its non-hard boundary voxels (candidates_, for phase 2) and those that qualify, the
  // planes side by side on the threads; the lists are then joined in plane order, so the
  // result is the same whatever the count. A plane's movable rows are one stretch of memory
  // (with the padding columns between them), read 64 states a test; the boundary voxels found
  // in it outside the movable columns are left out.
  absl::StatusOr<std::vector<int64_t>> ScanGrid(const ProgressRange& progress) {
    const auto& d = grid_.dims();
    const int planes = d[2] - 2 * kPadding;
    std::vector<std::vector<int64_t>> boundary(planes), found(planes);
    TaskCancel stop(cancel_, threads_, 1);
    progress.Begin(planes);
    RunTasks(threads_, planes, [&](int worker, int64_t plane) {
      if (stop.Poll(worker)) return;
      const int z = kPadding + static_cast<int>(plane);
      const VoxelState* const s = grid_.states().data();
      const int64_t begin = grid_.Index(0, kPadding, z);
      const int64_t end = grid_.Index(0, d[1] - kPadding, z);
      auto visit = [&](int64_t i) {
        const int x = static_cast<int>((i - begin) % d[0]);
        if (x < kPadding || x >= d[0] - kPadding || IsHard(s[i])) return;
        boundary[plane].push_back(i);
        if (Key(i) >= threshold_) found[plane].push_back(i);
      };
      int64_t i = begin;
      for (; i + 64 <= end; i += 64) {
        if (!AnyBoundary64(s + i)) continue;
        for (int k = 0; k < 8; ++k)
          for (uint64_t bits = BoundaryBits8(s + i + 8 * k); bits != 0; bits &= bits - 1)
            visit(i + 8 * k + std::countr_zero(bits) / 8);
      }
      for (; i < end; ++i)
        if (IsBoundary(s[i])) visit(i);
      progress.Add(1);
    });
    if (stop.fired()) return Cancel();
    candidates_ = Joined(boundary);
    return Joined(found);
  }

  // Phase 2's first qualifying voxels, in index order: the non-hard boundary voxels of the
  // movable region are those phase 1 started from and those it made boundary (a voxel leaves
  // or enters the boundary only by a step), so their sorted union, filtered, is what a scan
  // of the grid would find. Chunks of it are filtered on the threads and joined in order.
  absl::StatusOr<std::vector<int64_t>> FilterCandidates(const ProgressRange& progress) {
    std::sort(added_.begin(), added_.end());
    std::vector<int64_t> all;
    all.reserve(candidates_.size() + added_.size());
    std::set_union(candidates_.begin(), candidates_.end(), added_.begin(), added_.end(),
                   std::back_inserter(all));
    std::vector<int64_t>().swap(candidates_);
    std::vector<int64_t>().swap(added_);
    const int64_t n = static_cast<int64_t>(all.size());
    const int64_t tasks = (n + kCandidatesPerTask - 1) / kCandidatesPerTask;
    std::vector<std::vector<int64_t>> found(tasks);
    TaskCancel stop(cancel_, threads_, 1);
    progress.Begin(tasks);
    RunTasks(threads_, tasks, [&](int worker, int64_t task) {
      if (stop.Poll(worker)) return;
      const int64_t end = std::min(n, (task + 1) * kCandidatesPerTask);
      for (int64_t k = task * kCandidatesPerTask; k < end; ++k)
        if (Qualifies(all[k])) found[task].push_back(all[k]);
      progress.Add(1);
    });
    if (stop.fired()) return Cancel();
    return Joined(found);
  }

  static std::vector<int64_t> Joined(std::vector<std::vector<int64_t>>& lists) {
    size_t total = 0;
    for (const std::vector<int64_t>& list : lists) total += list.size();
    std::vector<int64_t> joined;
    joined.reserve(total);
    for (std::vector<int64_t>& list : lists) {
      joined.insert(joined.end(), list.begin(), list.end());
      std::vector<int64_t>().swap(list);
    }
    return joined;
  }

  bool InMovableRegion(int64_t i) const {
    const Coord c = grid_.CoordOf(i);
    for (int a = 0; a < 3; ++a)
      if (c[a] < kPadding || c[a] >= grid_.dim(a) - kPadding) return false;
    return true;
  }

  bool Movable(int64_t i) const {
    const VoxelState s = grid_.at(i);
    return IsBoundary(s) && !IsHard(s) && InMovableRegion(i);
  }

  // A voxel of the movable region that the phase would move now (its key is its bucket).
  bool Qualifies(int64_t i) const {
    const VoxelState s = grid_.at(i);
    return IsBoundary(s) && !IsHard(s) && Key(i) >= threshold_;
  }

  void Offer(int64_t i) {
    if (InMovableRegion(i) && Qualifies(i)) buckets_[Key(i)].items.push_back(i);
  }

  // Sets a state; when its category changes, the neighbours' DLC did: they are offered again
  // after the step.
  void Set(int64_t i, VoxelState s) {
    const int delta = Category(s) - Category(grid_.at(i));
    grid_.set(i, s);
    if (delta == 0) return;
    for (int64_t o : offsets_) touched_.push_back(i + o);
  }

  bool Simple(int64_t i) const { return IsSimple(NeighbourhoodMask(grid_, i, NonOutside)); }

  // Phase 1: V inside, its outside neighbours boundary, each added only while simple.
  bool StepInward(int64_t v, RelaxationStats& stats) {
    std::array<int64_t, 26> outside{};
    std::array<VoxelState, 26> old{};
    int n = 0;
    for (int64_t o : offsets_) {
      const int64_t w = v + o;
      if (!IsOutside(grid_.at(w))) continue;
      if (!InMovableRegion(w)) return false;
      outside[n++] = w;
    }
    for (int k = 0; k < n; ++k) {
      const int64_t w = outside[k];
      if (!Simple(w)) {
        for (int j = k - 1; j >= 0; --j) Set(outside[j], old[j]);
        ++stats.not_simple;
        return false;
      }
      old[k] = grid_.at(w);
      Set(w, kBoundarySoft);
      added_.push_back(w);
    }
    Set(v, static_cast<VoxelState>(grid_.at(v) & ~kBoundaryBit));
    ++stats.phase1_moves;
    stats.phase1_added += n;
    return true;
  }

  // Phase 2: V outside if simple, its inside neighbours boundary.
  bool StepOutward(int64_t v, RelaxationStats& stats) {
    if (!Simple(v)) {
      ++stats.not_simple;
      return false;
    }
    // Simple implies an outside face neighbour (T6 = 1): the new outside voxel joins it, so
    // the outside stays connected to the padding. Take its generation.
    int label = 0;
    const auto st = grid_.strides();
    for (int a = 0; a < 3; ++a)
      for (int64_t j : {v - st[a], v + st[a]})
        if (IsOutside(grid_.at(j))) label = GenerationLabel(grid_.at(j));
    std::array<int64_t, 26> inside{};
    int n = 0;
    for (int64_t o : offsets_) {
      const int64_t u = v + o;
      if (!IsInside(grid_.at(u))) continue;
      if (!InMovableRegion(u)) return false;
      inside[n++] = u;
    }
    Set(v, OutsideState(label));
    for (int k = 0; k < n; ++k)
      Set(inside[k], static_cast<VoxelState>(grid_.at(inside[k]) | kBoundaryBit));
    ++stats.phase2_moves;
    stats.phase2_uncovered += n;
    return true;
  }

  VoxelGrid& grid_;
  const int threshold_;
  const int threads_;
  const CancelToken& cancel_;
  const ProgressRange progress_;
  const std::array<int64_t, 26>& offsets_;
  // The first voxel of each row of the 3x3x3 block, from the centre's x - 1.
  const std::array<int64_t, 9> row_offsets_;
  std::array<Bucket, 27> buckets_;
  // The non-hard boundary voxels of the movable region when phase 1 started, in index order,
  // and the voxels phase 1 made boundary (some made outside again when a step was undone).
  std::vector<int64_t> candidates_, added_;
  int sign_ = -1;
  std::vector<int64_t> touched_;
};

}  // namespace

int DiscreteLocalCurvature(const VoxelGrid& grid, const Coord& c) {
  return SumOfCategories(grid.states().data() + grid.Index(c), grid.neighbour_offsets());
}

absl::StatusOr<RelaxationStats> Relax(VoxelGrid& membrane, const CancelToken& cancel,
                                      const RelaxationOptions& options, ProgressRange progress) {
  if (options.threshold < 1 || options.threshold > 26)
    return absl::InvalidArgumentError(
        absl::StrCat("relaxation threshold ", options.threshold, " is outside [1, 26]"));
  RelaxationStats stats;
  for (int a = 0; a < 3; ++a)
    if (membrane.dim(a) < 2 * kPadding + 1) return stats;  // no movable voxel
  Relaxer relaxer(membrane, options.threshold, options.threads, cancel, progress);
  if (absl::Status s = relaxer.Phase(-1, stats); !s.ok()) return s;
  if (absl::Status s = relaxer.Phase(+1, stats); !s.ok()) return s;
  return stats;
}

}  // namespace membrane

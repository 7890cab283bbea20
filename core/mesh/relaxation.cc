#include "core/mesh/relaxation.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "core/base/parallel_tasks.h"
#include "core/engine/huge_page_allocator.h"
#include "core/engine/local_topology.h"
#include "core/engine/voxel_state_words.h"

namespace membrane {
namespace {

constexpr int kPollSteps = 1024;
// The DLC's share of the progress; the two phases share the rest.
constexpr double kDlcShare = 1.0 / 3;
constexpr int64_t kVoxelsPerPoll = int64_t{1} << 18;
constexpr int kPadding = VoxelGrid::kPadding;

// What a voxel adds to its neighbours' DLC.
int Category(VoxelState s) { return IsOutside(s) ? 1 : IsInside(s) ? -1 : 0; }
bool NonOutside(VoxelState s) { return !IsOutside(s); }

// Grid-sized scratch bytes, uninitialised (see ComputeDlc), in 2 MB pages where the kernel gives
// them: with 4 KB pages the first touch of the three arrays faulted 3 times per 4 KB of grid,
// about as long as the relaxation's own work on the shared virtual machine.
struct FreeBytes {
  int64_t n = 0;
  void operator()(int8_t* p) const { HugePageAllocator<int8_t>().deallocate(p, n); }
};
using ByteArray = std::unique_ptr<int8_t[], FreeBytes>;
ByteArray NewByteArray(int64_t n) {
  return ByteArray(HugePageAllocator<int8_t>().allocate(static_cast<size_t>(n)), FreeBytes{n});
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
        offsets_(grid.neighbour_offsets()) {}

  // DLC of every voxel not on the array border, by three 1-D box sums of the categories. Each
  // pass is cut into chunks of kVoxelsPerPoll voxels, shared by the threads (a chunk writes only
  // its own voxels and reads arrays no pass of the moment writes, so the values do not depend
  // on the count); `cancel` is polled between chunks (a 430^3 grid is 80M voxels per pass). The
  // arrays are left uninitialised until a pass writes them: zero-filling 3 bytes per voxel up
  // front took over 100 ms without a poll, and the first touch by the pass's threads spreads
  // the kernel's page clearing over them too.
  absl::Status ComputeDlc() {
    const int64_t n = grid_.size(), sy = grid_.dim(0), sz = sy * grid_.dim(1);
    if (n < 3) return absl::OkStatus();  // Relax() lets no grid this small through
    ByteArray cat_array = NewByteArray(n), sum_array = NewByteArray(n);
    dlc_ = NewByteArray(n);
    // Raw pointers, captured by value and copied into each task: the byte stores could alias
    // anything reached through a reference, which would keep the loops from vectorizing.
    int8_t* const cat = cat_array.get();
    int8_t* const sum = sum_array.get();
    int8_t* const dlc = dlc_.get();
    const VoxelState* const s = grid_.states().data();
    // The five passes share the first third of the progress, a fifth each, chunk by chunk.
    int passes_done = 0;
    auto pass = [&](int64_t from, int64_t to, auto fn) -> absl::Status {
      const ProgressRange part =
          progress_.Part(kDlcShare * passes_done / 5, kDlcShare * (passes_done + 1) / 5);
      ++passes_done;
      // Asked before the pass too: a cancelled pass starts no threads.
      if (cancel_.cancelled()) return Cancel();
      if (to <= from) return absl::OkStatus();
      TaskCancel stop(cancel_, threads_, 1);
      const int64_t chunks = (to - from + kVoxelsPerPoll - 1) / kVoxelsPerPoll;
      part.Begin(chunks);
      RunTasks(threads_, chunks, [&stop, from, to, fn, part](int worker, int64_t task) {
        if (stop.Poll(worker)) return;
        const auto body = fn;
        const int64_t begin = from + task * kVoxelsPerPoll;
        const int64_t end = std::min(to, begin + kVoxelsPerPoll);
        for (int64_t i = begin; i < end; ++i) body(i);
        part.Add(1);
      });
      return stop.fired() ? Cancel() : absl::OkStatus();
    };
    // Each pass writes every voxel whose neighbours along its axis exist (across row ends
    // too: the values there are only read for border voxels, which never move), and the
    // rest are zeroed, so nothing uninitialised is ever read.
    absl::Status st =
        pass(0, n, [cat, s](int64_t i) { cat[i] = static_cast<int8_t>(Category(s[i])); });
    sum[0] = sum[n - 1] = 0;
    if (st.ok())
      st = pass(1, n - 1, [sum, cat](int64_t i) {
        sum[i] = static_cast<int8_t>(cat[i - 1] + cat[i] + cat[i + 1]);
      });
    std::fill(dlc, dlc + std::min(sy, n), 0);
    std::fill(dlc + std::max<int64_t>(n - sy, 0), dlc + n, 0);
    if (st.ok())
      st = pass(sy, n - sy, [dlc, sum, sy](int64_t i) {
        dlc[i] = static_cast<int8_t>(sum[i - sy] + sum[i] + sum[i + sy]);
      });
    if (st.ok())
      st = pass(sz, n - sz, [sum, dlc, sz](int64_t i) {
        sum[i] = static_cast<int8_t>(dlc[i - sz] + dlc[i] + dlc[i + sz]);
      });
    std::fill(dlc, dlc + std::min(sz, n), 0);
    std::fill(dlc + std::max<int64_t>(n - sz, 0), dlc + n, 0);
    if (st.ok())
      st = pass(sz, n - sz,
                [dlc, sum, cat](int64_t i) { dlc[i] = static_cast<int8_t>(sum[i] - cat[i]); });
    return st;
  }

  // sign = -1: phase 1 (DLC <= -threshold); +1: phase 2 (DLC >= threshold).
  absl::Status Phase(int sign, RelaxationStats& stats) {
    sign_ = sign;
    // Each phase has half of what the DLC leaves: its scan, then its steps, half each.
    const double phase_share = (1 - kDlcShare) / 2;
    const ProgressRange phase =
        sign < 0 ? progress_.Part(kDlcShare, kDlcShare + phase_share)
                 : progress_.Part(kDlcShare + phase_share, 1);
    const ProgressRange scan = phase.Part(0, 0.5), taken = phase.Part(0.5, 1);
    if (cancel_.cancelled()) return Cancel();
    for (auto& b : buckets_) {
      b.items.clear();
      b.next = 0;
    }
    // The scan: each z plane of the movable region lists its qualifying voxels in index order,
    // the planes side by side on the threads; the lists then fill the buckets plane after
    // plane, so the buckets' order is the index order whatever the count.
    const auto& d = grid_.dims();
    const int planes = d[2] - 2 * kPadding;
    std::vector<std::vector<int64_t>> found(planes);
    TaskCancel stop(cancel_, threads_, 1);
    scan.Begin(planes);
    RunTasks(threads_, planes, [&](int worker, int64_t plane) {
      if (stop.Poll(worker)) return;
      const int z = kPadding + static_cast<int>(plane);
      for (int y = kPadding; y < d[1] - kPadding; ++y)
        for (int x = kPadding; x < d[0] - kPadding;) {
          const int64_t i = grid_.Index(x, y, z);
          // Eight voxels at a time where none is a boundary voxel (most of the grid).
          if (x + 8 <= d[0] - kPadding && !AnyBoundary8(grid_.states().data() + i)) {
            x += 8;
            continue;
          }
          if (Qualifies(i)) found[plane].push_back(i);
          ++x;
        }
      scan.Add(1);
    });
    if (stop.fired()) return Cancel();
    int64_t first_found = 0;
    for (const std::vector<int64_t>& list : found) {
      for (int64_t i : list) buckets_[Key(i)].items.push_back(i);
      first_found += static_cast<int64_t>(list.size());
    }
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

  int Key(int64_t i) const { return sign_ * dlc_[i]; }

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
    if (Qualifies(i) && InMovableRegion(i)) buckets_[Key(i)].items.push_back(i);
  }

  // Sets a state and keeps the neighbours' DLC right.
  void Set(int64_t i, VoxelState s) {
    const int delta = Category(s) - Category(grid_.at(i));
    grid_.set(i, s);
    if (delta == 0) return;
    for (int64_t o : offsets_) {
      dlc_[i + o] = static_cast<int8_t>(dlc_[i + o] + delta);
      touched_.push_back(i + o);
    }
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
  ByteArray dlc_;
  std::array<Bucket, 27> buckets_;
  int sign_ = -1;
  std::vector<int64_t> touched_;
};

}  // namespace

int DiscreteLocalCurvature(const VoxelGrid& grid, const Coord& c) {
  const int64_t i = grid.Index(c);
  int dlc = 0;
  for (int64_t offset : grid.neighbour_offsets()) dlc += Category(grid.at(i + offset));
  return dlc;
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
  if (absl::Status s = relaxer.ComputeDlc(); !s.ok()) return s;
  if (absl::Status s = relaxer.Phase(-1, stats); !s.ok()) return s;
  if (absl::Status s = relaxer.Phase(+1, stats); !s.ok()) return s;
  return stats;
}

}  // namespace membrane

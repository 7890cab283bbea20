#include "core/engine/gap_refill.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <deque>
#include <limits>
#include <optional>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/container/flat_hash_set.h"
#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "core/base/parallel_tasks.h"
#include "core/engine/flat_bitset.h"
#include "core/engine/local_topology.h"
#include "core/engine/outside_blocks.h"
#include "core/engine/outside_runs.h"
#include "core/engine/state_planes.h"

namespace membrane {
namespace {

constexpr int64_t kCancelPoll = 1 << 16;
// A layer of the region's growth with fewer voxels to read stays on the calling thread: a
// voxel's read (up to six rays through the outside) costs about a microsecond, starting a
// thread tens of microseconds.
constexpr int64_t kMinLayerToSplit = 256;

// Where the hard voxels are. Per axis, per grid row along it: the lowest and highest
// coordinate of a hard voxel on the row (lowest > highest when none; rows numbered by
// AxisRowOf). And per block of 4 x 4 x 4 voxels, a bit set when the block holds a hard voxel:
// most voxels the region's growth reads are in a gap, where the whole box of the gap test
// would be read voxel by voxel across its planes.
class HardVoxelMap {
 public:
  // Read on `threads`, a slab of z planes a task: the rows along x and y lie in one plane and
  // belong to its task; those along z cross every slab and are met per task, then merged; a
  // block's bit is set by whichever task meets a hard voxel in it.
  HardVoxelMap(const VoxelGrid& grid, int threads) : dims_(grid.dims()) {
    const int nx = dims_[0], ny = dims_[1], nz = dims_[2];
    rows_[0] = static_cast<size_t>(ny) * nz;
    rows_[1] = static_cast<size_t>(nx) * nz;
    rows_[2] = static_cast<size_t>(nx) * ny;
    for (int d = 0; d < 3; ++d) {
      lo_[d].assign(rows_[d], kNoneLo);
      hi_[d].assign(rows_[d], kNoneHi);
      blocks_[d] = (dims_[d] + kBlock - 1) / kBlock;
    }
    block_bits_.assign(static_cast<size_t>(
                           (static_cast<int64_t>(blocks_[0]) * blocks_[1] * blocks_[2] + 63) / 64),
                       0);
    // At most kMaxSlabs: each slab past the first holds 8 bytes a z row of its own.
    const int slabs = std::clamp(std::min(threads, kMaxSlabs), 1, std::max(nz, 1));
    // Slab 0 writes the z rows' own arrays, the others theirs, merged below.
    std::vector<std::vector<int32_t>> z_lo(static_cast<size_t>(slabs - 1)),
        z_hi(static_cast<size_t>(slabs - 1));
    const VoxelState* s = grid.states().data();
    RunTasks(slabs, slabs, [&](int, int64_t slab) {
      int32_t* zl = lo_[2].data();
      int32_t* zh = hi_[2].data();
      if (slab > 0) {
        z_lo[slab - 1].assign(rows_[2], kNoneLo);
        z_hi[slab - 1].assign(rows_[2], kNoneHi);
        zl = z_lo[slab - 1].data();
        zh = z_hi[slab - 1].data();
      }
      const int z0 = static_cast<int>(nz * slab / slabs);
      const int z1 = static_cast<int>(nz * (slab + 1) / slabs);
      // Every voxel of the grid is read, hard ones are few: a row is searched for the next.
      for (int z = z0; z < z1; ++z)
        for (int y = 0; y < ny; ++y) {
          const VoxelState* row = s + grid.Index(0, y, z);
          for (int x = static_cast<int>(FirstHardOf(row, nx)); x < nx;
               x += 1 + static_cast<int>(FirstHardOf(row + x + 1, nx - x - 1))) {
            Note(lo_[0].data(), hi_[0].data(), AxisRowOf(dims_, 0, {x, y, z}), x);
            Note(lo_[1].data(), hi_[1].data(), AxisRowOf(dims_, 1, {x, y, z}), y);
            Note(zl, zh, AxisRowOf(dims_, 2, {x, y, z}), z);
            const int64_t b = BlockOf(x / kBlock, y / kBlock, z / kBlock);
            std::atomic_ref<uint64_t>(block_bits_[static_cast<size_t>(b >> 6)])
                .fetch_or(uint64_t{1} << (b & 63), std::memory_order_relaxed);
          }
        }
    });
    for (size_t k = 0; k < z_lo.size(); ++k)
      for (size_t r = 0; r < rows_[2]; ++r) {
        lo_[2][r] = std::min(lo_[2][r], z_lo[k][r]);
        hi_[2][r] = std::max(hi_[2][r], z_hi[k][r]);
      }
  }

  // True when the row of voxel c along axis d holds a hard voxel past coordinate t on the
  // side `sign`.
  bool HardPast(int d, const Coord& c, int t, int sign) const {
    const size_t row = AxisRowOf(dims_, d, c);
    return sign > 0 ? hi_[d][row] > t : lo_[d][row] < t;
  }

  // True when no block meeting the box of Chebyshev radius r around c (clipped to the array)
  // holds a hard voxel: then no voxel of the box is hard. False tells nothing.
  bool NoneNear(const Coord& c, int r) const {
    int lo[3], hi[3];
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::max(c[d] - r, 0) / kBlock;
      hi[d] = std::min(c[d] + r, dims_[d] - 1) / kBlock;
    }
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x) {
          const int64_t b = BlockOf(x, y, z);
          if ((block_bits_[static_cast<size_t>(b >> 6)] >> (b & 63)) & 1) return false;
        }
    return true;
  }

 private:
  int64_t BlockOf(int bx, int by, int bz) const {
    return bx + static_cast<int64_t>(blocks_[0]) * (by + static_cast<int64_t>(blocks_[1]) * bz);
  }
  static void Note(int32_t* lo, int32_t* hi, size_t row, int t) {
    lo[row] = std::min(lo[row], t);
    hi[row] = std::max(hi[row], t);
  }

  static constexpr int32_t kNoneLo = std::numeric_limits<int32_t>::max(), kNoneHi = -1;
  static constexpr int kMaxSlabs = 8;
  static constexpr int kBlock = 4;

  std::array<int, 3> dims_;
  std::array<size_t, 3> rows_;
  std::array<std::vector<int32_t>, 3> lo_, hi_;
  std::array<int, 3> blocks_{};
  std::vector<uint64_t> block_bits_;
};

// The walks through the outside along an axis: by the grid's runs (a binary search a walk)
// where they take at most an eighth of a byte a voxel, else by blocks of 8^3. The same stops.
class OutsideWalks {
 public:
  OutsideWalks(const VoxelGrid& grid, int threads)
      : runs_(OutsideRuns::Read(grid, threads, grid.size() / 8)) {
    if (!runs_) blocks_.emplace(grid, threads);
  }
  // OutsideRuns::WalkOutside's contract.
  int Walk(const VoxelGrid& grid, const Coord& c, int d, int sign) const {
    return runs_ ? runs_->WalkOutside(c, d, sign) : blocks_->WalkOutside(grid, c, d, sign);
  }

 private:
  std::optional<OutsideRuns> runs_;
  std::optional<OutsideBlocks> blocks_;
};

// Of the 6 axis rays from an outside voxel: those that meet a gap wall (the first non-outside
// voxel on the ray and the one after it are both soft or frozen: the ray enters the solid where
// it holds no data, and a hard voxel lies further on: the solid's far side), and those that
// leave through the outside to the array's border (the way out). A ray that meets the data
// first looks at a scanned wall from outside it. True when at least `min_gap_walls` rays meet
// gap walls and at most `max_open` leave. Each walk is a search of its row (OutsideWalks); the
// rays along z, whose stops read voxels a plane apart, go last, and the count stops once its
// answer is known.
bool BehindGapWalls(const VoxelGrid& grid, const HardVoxelMap& rows,
                    const OutsideWalks& walks, int64_t v, int min_gap_walls, int max_open) {
  const Coord c = grid.CoordOf(v);
  const int at[3] = {c.x, c.y, c.z};
  const auto st = grid.strides();
  int gap_walls = 0, open = 0, left = 6;
  for (int d = 0; d < 3; ++d)
    for (int sign = -1; sign <= 1; sign += 2) {
      if (gap_walls + left < min_gap_walls || open > max_open) return false;
      if (gap_walls >= min_gap_walls && open + left <= max_open) return true;
      --left;
      const int t = walks.Walk(grid, c, d, sign);
      const int64_t u = v + (t - at[d]) * st[d];
      if (t <= 0 || t >= grid.dim(d) - 1 || IsOutside(grid.at(u))) {
        ++open;
        continue;
      }
      if (IsHard(grid.at(u))) continue;
      const VoxelState next = grid.at(u + sign * st[d]);
      if (IsOutside(next) || IsHard(next)) continue;
      gap_walls += rows.HardPast(d, c, t + sign, sign);
    }
  return gap_walls >= min_gap_walls && open <= max_open;
}

// Of the 6 axis rays from an outside voxel, each walked at most `reach` voxels through
// non-hard voxels: those that meet a hard voxel with an outside voxel at most `depth` voxels
// behind it (a data wall with the outside beyond: seen from the object's inside), and those
// that leave to the array border without meeting a hard voxel.
struct PocketRays {
  int backed = 0;
  int open = 0;
};

// The count stops once fewer than `need` rays could still be backed (most outside voxels
// beside the membrane fail on their first two rays).
PocketRays CountPocketRays(const VoxelGrid& grid, int64_t v, int reach, int depth, int need) {
  const Coord c = grid.CoordOf(v);
  const int at[3] = {c.x, c.y, c.z};
  const auto st = grid.strides();
  PocketRays count;
  int tried = 0;
  for (int d = 0; d < 3; ++d)
    for (int sign = -1; sign <= 1; sign += 2) {
      if (count.backed + 6 - tried < need) return count;
      ++tried;
      int t = at[d] + sign;
      int64_t u = v + sign * st[d];
      int steps = 1;
      while (t > 0 && t < grid.dim(d) - 1 && steps <= reach && !IsHard(grid.at(u))) {
        t += sign;
        u += sign * st[d];
        ++steps;
      }
      if (t <= 0 || t >= grid.dim(d) - 1) {
        ++count.open;
        continue;
      }
      if (!IsHard(grid.at(u))) continue;
      for (int k = 1; k <= depth; ++k) {
        t += sign;
        u += sign * st[d];
        if (t < 0 || t > grid.dim(d) - 1) break;
        if (IsOutside(grid.at(u))) {
          ++count.backed;
          break;
        }
      }
    }
  return count;
}

// No hard voxel within Chebyshev distance r of c (voxels past the array count as none).
bool InGap(const VoxelGrid& grid, const HardVoxelMap& hard, const Coord& c, int r) {
  return hard.NoneNear(c, r) || !HardVoxelsWithin(grid, c, r, 1);
}

bool HasOutsideNeighbour(const VoxelGrid& grid, int64_t v) {
  for (int64_t off : grid.neighbour_offsets())
    if (IsOutside(grid.at(v + off))) return true;
  return false;
}

bool HasOutsideFaceNeighbour(const VoxelGrid& grid, int64_t v) {
  const auto st = grid.strides();
  for (int d = 0; d < 3; ++d)
    if (IsOutside(grid.at(v - st[d])) || IsOutside(grid.at(v + st[d]))) return true;
  return false;
}

bool HasSolidFaceNeighbour(const VoxelGrid& grid, int64_t v) {
  const auto st = grid.strides();
  for (int d = 0; d < 3; ++d)
    if (!IsOutside(grid.at(v - st[d])) || !IsOutside(grid.at(v + st[d]))) return true;
  return false;
}

// True when adding outside voxel v to the solid closes a loop of the outside and nothing
// else: the solid around v is one 26-component (no shells join), the outside around it two
// or more 6-components (T6), and those are still joined to each other without v (no
// cavity). Breadth-first searches through the outside from one voxel of each component run
// in turns, a step each, and join when they meet: a search that runs out first encloses a
// cavity (refused), and so does one that has visited kLoopSearch voxels in all.
constexpr int64_t kLoopSearch = int64_t{1} << 20;

bool ClosesLoop(const VoxelGrid& grid, int64_t v) {
  const uint32_t object = NeighbourhoodMask(grid, v, [](VoxelState x) { return !IsOutside(x); });
  if (CountT26(object & ~kCentreBit) != 1 || CountT6(~object & kAll27) < 2) return false;
  // One face neighbour of each local 6-component of the outside among the 18 neighbours.
  const uint32_t background = ~object & N18Mask();
  const std::array<int64_t, 27>& offsets = grid.block_offsets();
  std::vector<int64_t> seeds;
  uint32_t seen = 0;
  for (int k = 0; k < 27; ++k) {
    const uint32_t bit = 1u << k;
    if ((FaceNeighboursMask() & background & bit) == 0 || (seen & bit) != 0) continue;
    seen |= Flood6(bit, background);
    seeds.push_back(v + offsets[k]);
  }
  const int n = static_cast<int>(seeds.size());
  if (n < 2) return false;
  // owner[u]: the search that reached u first; group[i]: the searches search i has met.
  absl::flat_hash_map<int64_t, int> owner = {{v, -1}};
  std::vector<int> group(n);
  std::vector<std::deque<int64_t>> queues(n);
  for (int i = 0; i < n; ++i) {
    group[i] = i;
    owner[seeds[i]] = i;
    queues[i].push_back(seeds[i]);
  }
  auto root = [&](int i) {
    while (group[i] != i) i = group[i];
    return i;
  };
  int groups = n;
  const auto st = grid.strides();
  while (static_cast<int64_t>(owner.size()) < kLoopSearch) {
    for (int i = 0; i < n; ++i) {
      // A search whose group has another live search may run out: that one goes on.
      if (queues[i].empty()) {
        bool live = false;
        for (int j = 0; j < n; ++j) live |= root(j) == root(i) && !queues[j].empty();
        if (!live) return false;
        continue;
      }
      const int64_t u = queues[i].front();
      queues[i].pop_front();
      if (grid.OnArrayBorder(grid.CoordOf(u))) continue;
      for (int d = 0; d < 3; ++d)
        for (int64_t w : {u - st[d], u + st[d]}) {
          if (!IsOutside(grid.at(w))) continue;
          const auto [it, fresh] = owner.try_emplace(w, i);
          if (fresh) {
            queues[i].push_back(w);
            continue;
          }
          if (it->second < 0) continue;
          const int a = root(i), b = root(it->second);
          if (a == b) continue;
          group[a] = b;
          if (--groups == 1) return true;
        }
    }
  }
  return false;
}

// A pocket is the solid's interior seen through gaps in its scanned walls, so few of its
// voxels see the array border along an axis. A 6-component of the pocket voxels in which
// more than `max_open_share` of the voxels do (`open`: one ray to the border, the other five
// backed by data walls) is the inside of an open container seen through its mouth, a
// concavity: its voxels leave `pockets` and `region`.
void DropOpenPockets(const VoxelGrid& grid, double max_open_share,
                     const absl::flat_hash_set<int64_t>& open,
                     absl::flat_hash_set<int64_t>& pockets,
                     FlatBitset& region) {
  const auto st = grid.strides();
  absl::flat_hash_set<int64_t> seen;
  std::vector<int64_t> component, stack;
  std::vector<int64_t> dropped;
  for (int64_t start : pockets) {
    if (!seen.insert(start).second) continue;
    component.assign(1, start);
    stack.assign(1, start);
    int64_t open_count = 0;
    while (!stack.empty()) {
      const int64_t v = stack.back();
      stack.pop_back();
      open_count += open.contains(v);
      for (int d = 0; d < 3; ++d)
        for (int64_t u : {v - st[d], v + st[d]}) {
          if (!pockets.contains(u) || !seen.insert(u).second) continue;
          component.push_back(u);
          stack.push_back(u);
        }
    }
    if (open_count > max_open_share * static_cast<double>(component.size())) {
      dropped.insert(dropped.end(), component.begin(), component.end());
    }
  }
  for (int64_t v : dropped) {
    pockets.erase(v);
    region.reset(v);
  }
}

// The state a non-outside voxel takes from its neighbourhood: BOUNDARY when it touches the
// outside, INSIDE otherwise; a soft boundary voxel with an outside face neighbour is frozen.
VoxelState Settled(const VoxelGrid& grid, int64_t v) {
  VoxelState s = grid.at(v);
  if (!HasOutsideNeighbour(grid, v)) return static_cast<VoxelState>(s & ~kBoundaryBit);
  s |= kBoundaryBit;
  if (s == kBoundarySoft && HasOutsideFaceNeighbour(grid, v)) s = kBoundaryFrozen;
  return s;
}

}  // namespace

absl::StatusOr<GapRefillStats> RefillGapChannels(VoxelGrid& grid, const GapRefillOptions& options,
                                                 const CancelToken& cancel, int threads) {
  if (options.gap_radius < 1 || options.gap_radius > 16 || options.min_enclosed_rays < 1 ||
      options.min_enclosed_rays > 6 || options.max_open_rays < 0 || options.max_open_rays > 6 ||
      options.pocket_backed_rays < 0 || options.pocket_backed_rays > 6 ||
      options.pocket_wall_depth < 1 || options.pocket_wall_depth > 8 ||
      options.pocket_reach < 1 || options.pocket_reach > 256 || options.max_pocket_loops < 0 ||
      !(options.max_open_pocket_share >= 0 && options.max_open_pocket_share <= 1)) {
    return absl::InvalidArgumentError(absl::StrCat(
        "gap refill options out of range: gap_radius ", options.gap_radius,
        " (1..16), min_enclosed_rays ", options.min_enclosed_rays, " (1..6), max_open_rays ",
        options.max_open_rays, " (0..6), pocket_backed_rays ", options.pocket_backed_rays,
        " (0..6), pocket_wall_depth ", options.pocket_wall_depth, " (1..8), pocket_reach ",
        options.pocket_reach, " (1..256), max_pocket_loops ", options.max_pocket_loops,
        " (>= 0), max_open_pocket_share ", options.max_open_pocket_share, " (0..1)"));
  }
  GapRefillStats stats;
  if (!options.enabled) return stats;
  const HardVoxelMap hard(grid, threads);
  const OutsideWalks walks(grid, threads);
  // The region to refill is read on the membrane as the shrink left it (the fill itself
  // changes what the rays meet): the outside voxels in a gap and behind gap walls, reached
  // from the membrane through such voxels. Reading a voxel writes nothing: the seeds below
  // are read on the threads.
  enum class Reading { kOut, kGap, kPocket, kOpenPocket };
  auto read = [&](int64_t v) {
    if (!IsOutside(grid.at(v)) || grid.OnArrayBorder(grid.CoordOf(v))) return Reading::kOut;
    if (InGap(grid, hard, grid.CoordOf(v), options.gap_radius) &&
        BehindGapWalls(grid, hard, walks, v, options.min_enclosed_rays, options.max_open_rays)) {
      return Reading::kGap;
    }
    if (options.pocket_backed_rays == 0 || GenerationLabel(grid.at(v)) == 0)
      return Reading::kOut;
    const PocketRays count = CountPocketRays(grid, v, options.pocket_reach,
                                             options.pocket_wall_depth,
                                             options.pocket_backed_rays);
    if (count.backed < options.pocket_backed_rays || count.open > options.max_open_rays)
      return Reading::kOut;
    return count.open > 0 ? Reading::kOpenPocket : Reading::kPocket;
  };
  // The region and the voxels read out of it as bits over the grid (256 MB each on a 2e9-voxel
  // grid, where hash sets of the 10M-point spot scan's 3.9M and 2.0M voxels cost a cache miss
  // a look-up); the pockets are few.
  FlatBitset region(grid.size(), nullptr, FlatBitset::Unset{});
  FlatBitset rejected(grid.size(), nullptr, FlatBitset::Unset{});
  region.set_threads(threads);
  rejected.set_threads(threads);
  region.clear_all();
  rejected.clear_all();
  absl::flat_hash_set<int64_t> pockets, open_pockets;
  std::vector<int64_t> frontier;
  // Notes a voxel read in the region; true when it is.
  auto note = [&](int64_t v, Reading reading) {
    if (reading == Reading::kOut) return false;
    if (reading == Reading::kOpenPocket) open_pockets.insert(v);
    if (reading != Reading::kGap) pockets.insert(v);
    region.set(v);
    frontier.push_back(v);
    return true;
  };
  // Seeds in voxel order, off the array border, a z plane a task. This loop reads the whole
  // grid, mostly outside voxels by now: it walks rows (no division for the border test) and
  // finds the outside voxels beside the solid eight at a time, with seven word loads.
  const auto& dims = grid.dims();
  const auto st = grid.strides();
  const VoxelState* states = grid.states().data();
  std::vector<std::vector<std::pair<int64_t, Reading>>> seeds_of(
      static_cast<size_t>(std::max(dims[2] - 2, 0)));
  TaskCancel task_cancel(cancel, threads, 64);
  RunTasks(threads, static_cast<int64_t>(seeds_of.size()), [&](int worker, int64_t task) {
    const int z = static_cast<int>(task) + 1;
    std::vector<std::pair<int64_t, Reading>>& out = seeds_of[static_cast<size_t>(task)];
    for (int y = 1; y < dims[1] - 1; ++y) {
      if (task_cancel.Poll(worker)) return;
      const int64_t row = grid.Index(0, y, z);
      const int64_t end = row + dims[0] - 1;
      int64_t v = row + 1;
      for (; v + 8 <= end; v += 8)
        for (uint64_t m = OutsideBesideSolidOfEight(states + v, st.data()); m != 0;
             m &= m - 1) {
          const int64_t u = v + __builtin_ctzll(m) / 8;
          const Reading reading = read(u);
          if (reading != Reading::kOut) out.emplace_back(u, reading);
        }
      for (; v < end; ++v)
        if (IsOutside(states[v]) && HasSolidFaceNeighbour(grid, v)) {
          const Reading reading = read(v);
          if (reading != Reading::kOut) out.emplace_back(v, reading);
        }
    }
  });
  if (task_cancel.fired()) return absl::CancelledError("gap refill cancelled");
  for (const auto& list : seeds_of)
    for (const auto& [v, reading] : list) note(v, reading);
  seeds_of.clear();
  const std::vector<int64_t> first = frontier;
  // The region grows a layer at a time: the voxels beside the last layer that are neither in
  // the region nor rejected are read on the threads (reading writes nothing), then noted in
  // index order, the region's voxels among them making the next layer. The region, its pockets
  // and the rejected voxels are the closure of the seeds under `read`, so they are the same
  // sets in any order of growth and on any thread count.
  std::vector<int64_t> layer;
  std::vector<Reading> readings;
  while (!frontier.empty()) {
    if (cancel.cancelled()) return absl::CancelledError("gap refill cancelled");
    layer.clear();
    for (int64_t v : frontier)
      for (int d = 0; d < 3; ++d)
        for (int64_t u : {v - st[d], v + st[d]})
          if (IsOutside(grid.at(u)) && !region.test(u) && !rejected.test(u)) layer.push_back(u);
    frontier.clear();
    std::sort(layer.begin(), layer.end());
    layer.erase(std::unique(layer.begin(), layer.end()), layer.end());
    readings.resize(layer.size());
    const TaskRanges ranges =
        TaskRanges::Split(static_cast<int64_t>(layer.size()), threads, 4, kMinLayerToSplit);
    RunTasks(threads, ranges.tasks, [&](int, int64_t task) {
      for (int64_t i = ranges.begin(task); i < ranges.end(task); ++i) readings[i] = read(layer[i]);
    });
    for (size_t i = 0; i < layer.size(); ++i)
      if (!note(layer[i], readings[i])) rejected.set(layer[i]);
  }
  DropOpenPockets(grid, options.max_open_pocket_share, open_pockets, pockets, region);
  std::vector<int64_t> seeds;
  for (int64_t v : first) {
    if (region.test(v)) seeds.push_back(v);
  }
  stats.pocket_voxels = static_cast<int64_t>(pockets.size());
  // Fill from the membrane inwards, each voxel when it is beside the solid and simple; a
  // voxel not simple yet is tried again when a neighbour joins the solid. When none is left,
  // one pocket voxel whose addition closes a loop of the outside is added (the lowest index,
  // for the same result on every run), and the simple fill goes on around it.
  std::deque<int64_t> queue(seeds.begin(), seeds.end());
  std::vector<int64_t> touched;
  absl::flat_hash_set<int64_t> refused;  // pocket voxels whose addition closed no loop
  int64_t steps = 0;
  auto add = [&](int64_t v) {
    grid.set(v, kInsideSoft);
    ++stats.refilled_voxels;
    touched.push_back(v);
    for (int64_t off : grid.neighbour_offsets())
      if (IsOutside(grid.at(v + off)) && region.test(v + off)) queue.push_back(v + off);
  };
  for (;;) {
    while (!queue.empty()) {
      if (++steps % kCancelPoll == 0 && cancel.cancelled()) break;
      const int64_t v = queue.front();
      queue.pop_front();
      if (!IsOutside(grid.at(v)) || !HasSolidFaceNeighbour(grid, v)) continue;
      const uint32_t object =
          NeighbourhoodMask(grid, v, [](VoxelState x) { return !IsOutside(x); });
      if (!IsSimple(object)) continue;
      add(v);
    }
    if (cancel.cancelled() || stats.loops_closed >= options.max_pocket_loops) break;
    std::vector<int64_t> candidates;
    for (int64_t v : pockets)
      if (IsOutside(grid.at(v)) && HasSolidFaceNeighbour(grid, v) && !refused.contains(v))
        candidates.push_back(v);
    std::sort(candidates.begin(), candidates.end());
    bool closed = false;
    for (int64_t v : candidates) {
      if (ClosesLoop(grid, v)) {
        add(v);
        ++stats.loops_closed;
        closed = true;
        break;
      }
      refused.insert(v);
    }
    if (!closed) break;
  }
  // Settle the positions of the refilled voxels and of the solid around them, each once
  // (`rejected` marks them now): settling changes no voxel's outside bit, so a voxel settles
  // to the same state whenever it is settled, and again to the same.
  rejected.clear_all();
  auto settle = [&](int64_t v) {
    if (rejected.test(v)) return;
    rejected.set(v);
    grid.set(v, Settled(grid, v));
  };
  for (int64_t v : touched) {
    settle(v);
    for (int64_t off : grid.neighbour_offsets())
      if (!IsOutside(grid.at(v + off))) settle(v + off);
  }
  if (cancel.cancelled()) return absl::CancelledError("gap refill cancelled");
  return stats;
}

}  // namespace membrane

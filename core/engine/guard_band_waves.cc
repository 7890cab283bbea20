#include "core/engine/guard_band_waves.h"

#include <algorithm>
#include <atomic>
#include <utility>

#include "absl/status/status.h"
#include "core/base/parallel_tasks.h"

namespace membrane {
namespace {

constexpr int kPad = VoxelGrid::kPadding;

// The six face directions, in the order of Bricks::Push: +x, -x, +y, -y, +z, -z.
constexpr int kDirections = 6;
constexpr int Opposite(int dir) { return dir ^ 1; }

// Bit x + k y + k^2 z of a brick is fine voxel (x, y, z) of its coarse voxel.
class Bricks {
 public:
  explicit Bricks(int k) : k_(k) {
    const int n = k * k * k;
    full_ = n == 64 ? ~uint64_t{0} : (uint64_t{1} << n) - 1;
    for (int b = 0; b < n; ++b) {
      const int x = b % k, y = b / k % k;
      const uint64_t bit = uint64_t{1} << b;
      if (x == 0) x0_ |= bit;
      if (x == k - 1) xl_ |= bit;
      if (y == 0) y0_ |= bit;
      if (y == k - 1) yl_ |= bit;
    }
  }
  uint64_t full() const { return full_; }
  // The bits w and their face neighbours inside the brick.
  uint64_t Within(uint64_t w) const {
    const int k2 = k_ * k_;
    return (w | ((w << 1) & ~x0_) | ((w >> 1) & ~xl_) | ((w << k_) & ~y0_) | ((w >> k_) & ~yl_) |
            (w << k2) | (w >> k2)) &
           full_;
  }
  // The bits of the brick one step along `dir` that are face neighbours of bits w.
  uint64_t Push(uint64_t w, int dir) const {
    const int kx = k_ - 1, ky = k_ * (k_ - 1), kz = k_ * k_ * (k_ - 1);
    switch (dir) {
      case 0: return (w >> kx) & x0_;
      case 1: return (w << kx) & xl_;
      case 2: return (w >> ky) & y0_;
      case 3: return (w << ky) & yl_;
      case 4: return w >> kz;
      default: return (w << kz) & full_;
    }
  }

 private:
  int k_;
  uint64_t full_ = 0, x0_ = 0, xl_ = 0, y0_ = 0, yl_ = 0;
};

// A brick's fine voxels in the grid.
class BrickVoxels {
 public:
  BrickVoxels(const VoxelGrid& grid, const std::array<int, 3>& coarse_dims, int k,
              uint64_t full)
      : grid_(grid), cd_(coarse_dims), k_(k), full_(full) {
    for (int z = 0; z < k; ++z)
      for (int y = 0; y < k; ++y)
        for (int x = 0; x < k; ++x) offsets_.push_back(grid.Index(x, y, z));
  }
  // The fine index of bit 0 of coarse voxel c, and its fine corner.
  Coord Corner(int64_t c) const {
    const int64_t plane = static_cast<int64_t>(cd_[0]) * cd_[1];
    const int cx = static_cast<int>(c % cd_[0]), cy = static_cast<int>(c / cd_[0] % cd_[1]),
              cz = static_cast<int>(c / plane);
    return Coord{kPad + (cx - kPad) * k_, kPad + (cy - kPad) * k_, kPad + (cz - kPad) * k_};
  }
  int64_t Base(int64_t c) const { return grid_.Index(Corner(c)); }
  int64_t Offset(int bit) const { return offsets_[static_cast<size_t>(bit)]; }

  // The brick's bits of INSIDE soft voxels in the data region (`soft`), of voxels out of it
  // or boundary (`open`) and of INSIDE frozen voxels (`frozen`).
  void Read(int64_t c, uint64_t& soft, uint64_t& open, uint64_t& frozen) const {
    soft = frozen = 0;
    open = full_;
    const Coord f = Corner(c);
    std::array<int, 3> lo, hi;
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::max(0, kPad - f[d]);
      hi[d] = std::min(k_, grid_.dim(d) - kPad - f[d]);
    }
    const VoxelState* states = grid_.states().data() + grid_.Index(f);
    for (int z = lo[2]; z < hi[2]; ++z)
      for (int y = lo[1]; y < hi[1]; ++y) {
        const int bit0 = k_ * (y + k_ * z);
        const VoxelState* row = states + offsets_[static_cast<size_t>(bit0)];
        for (int x = lo[0]; x < hi[0]; ++x) {
          const VoxelState s = row[x];
          const uint64_t b = uint64_t{1} << (bit0 + x);
          soft |= s == kInsideSoft ? b : 0;
          frozen |= s == kInsideFrozen ? b : 0;
          open &= s == kBoundarySoft ? ~uint64_t{0} : ~b;
        }
      }
  }

  // The brick's bits of voxels with a hard voxel among their 26 neighbours (or hard
  // themselves): the hard voxels of the (k + 2)^3 block around the brick, dilated.
  uint64_t NearHard(int64_t c) const {
    const Coord f = Corner(c);
    const int n = k_ + 2;
    uint32_t rows[6][6] = {};  // [z][y], bit x: a hard voxel at x - 1 .. x + 1 of the block
    for (int z = 0; z < n; ++z) {
      if (f.z - 1 + z >= grid_.dim(2)) break;
      for (int y = 0; y < n; ++y) {
        if (f.y - 1 + y >= grid_.dim(1)) break;
        const VoxelState* row =
            grid_.states().data() + grid_.Index(f.x - 1, f.y - 1 + y, f.z - 1 + z);
        const int nx = std::min(n, grid_.dim(0) - (f.x - 1));
        uint32_t r = 0;
        for (int x = 0; x < nx; ++x) r |= static_cast<uint32_t>(IsHard(row[x])) << x;
        rows[z][y] = r | (r << 1) | (r >> 1);
      }
    }
    uint64_t near = 0;
    const uint32_t row_bits = (1u << k_) - 1;
    for (int z = 0; z < k_; ++z)
      for (int y = 0; y < k_; ++y) {
        uint32_t m = 0;
        for (int dz = 0; dz < 3; ++dz)
          m |= rows[z + dz][y] | rows[z + dz][y + 1] | rows[z + dz][y + 2];
        near |= static_cast<uint64_t>((m >> 1) & row_bits) << (k_ * (y + k_ * z));
      }
    return near;
  }

 private:
  const VoxelGrid& grid_;
  std::array<int, 3> cd_;
  int k_;
  uint64_t full_;
  std::vector<int64_t> offsets_;
};

// Band bricks by their index in the band's list.
using Front = std::vector<std::pair<int32_t, uint64_t>>;

}  // namespace

absl::StatusOr<int64_t> FreezeBandByWaves(VoxelGrid& grid, const std::array<int, 3>& coarse_dims,
                                          int k, const std::vector<uint8_t>& classes,
                                          const std::vector<int64_t>& band_voxels,
                                          const CancelToken& cancel, int threads) {
  const Bricks bricks(k);
  const BrickVoxels voxels(grid, coarse_dims, k, bricks.full());
  const int64_t cx = 1, cy = coarse_dims[0], cz = cy * coarse_dims[1];
  const std::array<int64_t, kDirections> steps = {cx, -cx, cy, -cy, cz, -cz};
  // Each band brick's place in band_voxels, -1 for the other coarse voxels: the waves' words
  // are kept for the band's bricks only.
  std::vector<int32_t> slot(classes.size(), -1);
  const int32_t bands = static_cast<int32_t>(band_voxels.size());
  for (int32_t i = 0; i < bands; ++i) slot[static_cast<size_t>(band_voxels[i])] = i;
  // `avail`: the band's soft voxels no wave has reached; `acc`: a step's reached bits (and,
  // before the waves, the bricks' open bits), zero outside the bricks a step touches;
  // `near`: NearHard, read when the core's wave first comes to a brick.
  std::vector<uint64_t> avail(bands), acc(bands), near(bands);
  std::vector<uint8_t> near_read(bands, 0);
  // The bricks' reads and the waves' first step run a range of bricks a task: each task
  // writes only its own bricks' words (the freezes wait until every task is done, so no task
  // reads a state another writes).
  const TaskRanges split = TaskRanges::Split(bands, threads, 16);
  const int64_t ranges = split.tasks;
  const auto range_of = [&](int64_t task) {
    return std::pair<int32_t, int32_t>(static_cast<int32_t>(split.begin(task)),
                                       static_cast<int32_t>(split.end(task)));
  };
  RunTasks(threads, ranges, [&](int, int64_t task) {
    const auto [first, end] = range_of(task);
    for (int32_t i = first; i < end; ++i) {
      uint64_t frozen;
      voxels.Read(band_voxels[i], avail[i], acc[i], frozen);
    }
  });
  const auto off_data = [&](int32_t i, uint64_t w) {
    if (!near_read[i]) {
      near[i] = voxels.NearHard(band_voxels[i]);
      near_read[i] = 1;
    }
    return w & ~near[i];
  };
  int64_t frozen_count = 0;
  // Freezes brick i's bits w; returns how many.
  const auto freeze_bits = [&](int32_t i, uint64_t w) {
    const int64_t base = voxels.Base(band_voxels[i]);
    const int64_t count = __builtin_popcountll(w);
    while (w != 0) {
      const int bit = __builtin_ctzll(w);
      w &= w - 1;
      grid.set(base + voxels.Offset(bit), kInsideFrozen);
    }
    return count;
  };

  // The first step of both waves, from their sources into each band brick: the outside's
  // from the open bits of the brick and its neighbours (every bit of an outside coarse voxel),
  // the core's from its frozen neighbours.
  Front outside, core;
  // The band's face neighbours of each band brick (-1: none), so that a step reads no more
  // of the coarse grid.
  std::vector<std::array<int32_t, kDirections>> neighbours(bands);
  std::vector<Front> outside_of(static_cast<size_t>(ranges)), core_of(static_cast<size_t>(ranges));
  RunTasks(threads, ranges, [&](int, int64_t task) {
    const auto [first, end] = range_of(task);
    for (int32_t i = first; i < end; ++i) {
      const int64_t t = band_voxels[i];
      uint64_t open = bricks.Within(acc[i]), from_core = 0;
      for (int dir = 0; dir < kDirections; ++dir) {
        const int64_t n = t + steps[dir];
        neighbours[i][dir] = slot[n];
        uint64_t n_open, n_frozen = 0;
        if (slot[n] >= 0) {
          n_open = acc[slot[n]];
        } else if (classes[n] == kCoarseOutside) {
          n_open = bricks.full();
        } else {
          uint64_t soft;
          voxels.Read(n, soft, n_open, n_frozen);
        }
        open |= bricks.Push(n_open, Opposite(dir));
        from_core |= bricks.Push(n_frozen, Opposite(dir));
      }
      const uint64_t o = open & avail[i];
      const uint64_t c =
          from_core & avail[i] & ~o ? off_data(i, from_core & avail[i] & ~o) : 0;
      avail[i] &= ~(o | c);
      if (o != 0) outside_of[task].emplace_back(i, o);
      if (c != 0) core_of[task].emplace_back(i, c);
    }
  });
  for (int64_t task = 0; task < ranges; ++task) {
    outside.insert(outside.end(), outside_of[task].begin(), outside_of[task].end());
    core.insert(core.end(), core_of[task].begin(), core_of[task].end());
  }
  std::vector<int64_t> core_frozen(static_cast<size_t>(ranges), 0);
  RunTasks(threads, ranges, [&](int, int64_t task) {
    for (const auto& [i, w] : core_of[task]) core_frozen[task] += freeze_bits(i, w);
  });
  for (int64_t f : core_frozen) frozen_count += f;
  std::fill(acc.begin(), acc.end(), 0);
  slot = std::vector<int32_t>();

  // A step: the bits each front brick reaches in itself and its neighbours are or-ed into
  // `acc` (atomically where the front is split between tasks), the brick whose `acc` was zero
  // listing it as touched; then each touched brick's bits become the next front (the core's
  // off the data, frozen once every task has read the grid). The sets reached do not depend
  // on the order, so any thread count gives the same voxels.
  constexpr size_t kMinSplitFront = 4096;
  std::vector<std::vector<int32_t>> touched_of;
  std::vector<Front> next_of;
  const auto advance = [&](Front& front, bool is_core) {
    const int64_t parts =
        front.size() < kMinSplitFront ? 1 : std::min<int64_t>(16 * int64_t{threads},
                                                             static_cast<int64_t>(front.size()));
    touched_of.assign(static_cast<size_t>(parts), {});
    next_of.assign(static_cast<size_t>(parts), {});
    const int64_t size = static_cast<int64_t>(front.size());
    RunTasks(parts > 1 ? threads : 1, parts, [&](int, int64_t part) {
      std::vector<int32_t>& touched = touched_of[static_cast<size_t>(part)];
      const auto reach = [&](int32_t i, uint64_t w) {
        w &= avail[i];
        if (w == 0) return;
        if (std::atomic_ref<uint64_t>(acc[i]).fetch_or(w, std::memory_order_relaxed) == 0) {
          touched.push_back(i);
        }
      };
      for (int64_t e = size * part / parts; e < size * (part + 1) / parts; ++e) {
        const auto& [i, w] = front[static_cast<size_t>(e)];
        reach(i, bricks.Within(w));
        const std::array<int32_t, kDirections>& around = neighbours[i];
        for (int dir = 0; dir < kDirections; ++dir) {
          if (around[dir] < 0) continue;
          const uint64_t p = bricks.Push(w, dir);
          if (p != 0) reach(around[dir], p);
        }
      }
    });
    RunTasks(parts > 1 ? threads : 1, parts, [&](int, int64_t part) {
      Front& reached = next_of[static_cast<size_t>(part)];
      for (int32_t i : touched_of[static_cast<size_t>(part)]) {
        uint64_t w = acc[i];
        acc[i] = 0;
        if (is_core) w = off_data(i, w);
        if (w == 0) continue;
        avail[i] &= ~w;
        reached.emplace_back(i, w);
      }
    });
    front.clear();
    for (const Front& reached : next_of) front.insert(front.end(), reached.begin(), reached.end());
    if (!is_core) return;
    std::vector<int64_t> counts(static_cast<size_t>(parts), 0);
    RunTasks(parts > 1 ? threads : 1, parts, [&](int, int64_t part) {
      for (const auto& [i, w] : next_of[static_cast<size_t>(part)]) {
        counts[static_cast<size_t>(part)] += freeze_bits(i, w);
      }
    });
    for (int64_t c : counts) frozen_count += c;
  };
  while (!outside.empty() || !core.empty()) {
    if (cancel.cancelled()) {
      return absl::CancelledError("reconstruction cancelled while guarding interiors");
    }
    advance(outside, false);
    advance(core, true);
  }
  return frozen_count;
}

}  // namespace membrane

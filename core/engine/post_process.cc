#include "core/engine/post_process.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/types/span.h"
#include "core/base/parallel_tasks.h"
#include "core/engine/flat_bitset.h"
#include "core/engine/local_topology.h"
#include "core/engine/state_planes.h"

namespace membrane {
namespace {

// Bounds one search: the interior of a hollowed model can be large, and an inside hard voxel
// far from the membrane is better left (and counted) than found by a scan of the whole solid.
constexpr size_t kMaxVisited = 200000;
// Bounds all searches together, in voxels visited per voxel of the grid: each search is
// bounded, but not their number. With the dead components skipped (below), the ten real scans
// use 0.000-0.019 per voxel, noisy spheres up to 0.25 (a sealed interior at a coarse voxel);
// past the bound the remaining inside hard voxels are left (and counted) rather than a hostile
// cloud keeping a worker busy for hours. (The floods that find dead components visit each
// voxel once at most, outside this count.)
constexpr int64_t kMaxVisitsPerVoxel = 4;

// The parent links of one breadth-first search, voxel -> the voxel it was reached from: an
// open-addressing table reused from search to search and cleared through its list of used
// slots. The searches are many (one per inside hard voxel: 24k on the 3M-point bunny scan at
// its noise-aware voxel) and each may see kMaxVisited voxels, where a hash map allocated per
// search spent a third of the whole run in its inserts and lookups.
class ParentLinks {
 public:
  size_t size() const { return used_.size(); }
  void Clear() {
    for (const size_t slot : used_) keys_[slot] = kEmpty;
    used_.clear();
  }
  bool Contains(int64_t voxel) const { return keys_[Find(voxel)] == voxel; }
  // `voxel` (>= 0) must not be in the table yet.
  void Insert(int64_t voxel, int64_t parent) {
    if (2 * (used_.size() + 1) > keys_.size()) Grow();
    const size_t slot = Find(voxel);
    keys_[slot] = voxel;
    parents_[slot] = parent;
    used_.push_back(slot);
  }
  // The parent of `voxel`, which must be in the table.
  int64_t Parent(int64_t voxel) const { return parents_[Find(voxel)]; }
  template <typename F>
  void ForEachVoxel(F f) const {
    for (const size_t slot : used_) f(keys_[slot]);
  }

 private:
  static constexpr int64_t kEmpty = -1;  // voxel indices are >= 0
  // The slot holding `voxel`, or the empty slot where it would go (linear probing).
  size_t Find(int64_t voxel) const {
    const size_t mask = keys_.size() - 1;
    size_t slot = static_cast<size_t>((static_cast<uint64_t>(voxel) * 0x9E3779B97F4A7C15ull) >>
                                      shift_) & mask;
    while (keys_[slot] != kEmpty && keys_[slot] != voxel) slot = (slot + 1) & mask;
    return slot;
  }
  void Grow() {
    std::vector<int64_t> keys(2 * keys_.size(), kEmpty);
    std::vector<int64_t> parents(keys.size());
    std::vector<size_t> used;
    used.reserve(used_.size());
    std::swap(keys, keys_);
    std::swap(parents, parents_);
    shift_ = 64 - std::countr_zero(keys_.size());
    for (const size_t old : used_) {
      const size_t slot = Find(keys[old]);
      keys_[slot] = keys[old];
      parents_[slot] = parents[old];
      used.push_back(slot);
    }
    used_ = std::move(used);
  }
  static constexpr int kFirstBits = 10;
  std::vector<int64_t> keys_ = std::vector<int64_t>(size_t{1} << kFirstBits, kEmpty);
  std::vector<int64_t> parents_ = std::vector<int64_t>(size_t{1} << kFirstBits);
  std::vector<size_t> used_;
  int shift_ = 64 - kFirstBits;  // the hash's top bits index the table
};

bool HasOutsideFaceNeighbour(const VoxelState* s, int64_t i, const std::array<int64_t, 3>& st) {
  for (int d = 0; d < 3; ++d)
    if (IsOutside(s[i - st[d]]) || IsOutside(s[i + st[d]])) return true;
  return false;
}

}  // namespace

void CarveToOutside(VoxelGrid& grid, int64_t i) {
  const std::array<int64_t, 27>& offsets = grid.block_offsets();
  VoxelState* s = grid.mutable_states().data();
  s[i] = OutsideState(0);
  for (int k = 0; k < 27; ++k) {
    VoxelState& n = s[i + offsets[k]];
    if (IsInside(n)) n |= kBoundaryBit;
    if (IsFaceStep(k) && n == kBoundarySoft) n = kBoundaryFrozen;
  }
}

absl::StatusOr<PostProcessStats> ConnectInsideHardVoxels(VoxelGrid& grid,
                                                         const CancelToken& cancel,
                                                         int max_path, int threads) {
  PostProcessStats stats;
  const auto st = grid.strides();
  const int64_t nv = grid.size();
  std::vector<int64_t> targets;
  // Inside and hard is exactly the state kInsideHard: memchr jumps between them.
  const VoxelState* first = grid.states().data();
  for (const void* p = std::memchr(first, kInsideHard, static_cast<size_t>(nv)); p != nullptr;) {
    const int64_t i = static_cast<const VoxelState*>(p) - first;
    targets.push_back(i);
    p = std::memchr(first + i + 1, kInsideHard, static_cast<size_t>(nv - i - 1));
  }
  stats.inside_hard_before = static_cast<int64_t>(targets.size());

  const int64_t steps[6] = {-st[0], st[0], -st[1], st[1], -st[2], st[2]};
  // Soft voxels of components (6-connected soft non-outside voxels) known to hold no voxel
  // with an outside face neighbour. A search skips them: they cannot lead out, and stay so,
  // since carving only makes outside voxels of components that do lead out, which share no
  // face with another component. Without this, every inside hard voxel on the wall of a sealed
  // interior searched that interior again: 38k of them on a thick noisy sphere took 55 s.
  FlatBitset dead;
  // Soft voxels a full flood (below) has reached: flooding them again would find the same.
  FlatBitset flooded;
  if (!targets.empty()) {  // most clouds leave none: no grid-sized bitsets then
    dead.EnsureSize(nv);
    flooded.EnsureSize(nv);
  }
  int64_t visits_left = kMaxVisitsPerVoxel * nv;
  ParentLinks parent;
  std::vector<std::pair<int64_t, int>> queue;  // the search's voxels and depths, in order
  std::vector<int64_t> stack;
  std::vector<int64_t> component;
  // Floods the soft component of `start` (not yet dead or flooded) to its end, however far,
  // and marks it dead when no voxel of it has an outside face neighbour.
  auto flood = [&](int64_t start) {
    const VoxelState* s = grid.states().data();
    component.assign(1, start);
    stack.assign(1, start);
    flooded.set(start);
    bool leads_out = false;
    while (!stack.empty()) {
      const int64_t i = stack.back();
      stack.pop_back();
      if (HasOutsideFaceNeighbour(s, i, st)) leads_out = true;
      for (int64_t step : steps) {
        const int64_t j = i + step;
        if (IsOutside(s[j]) || IsHard(s[j]) || flooded.test(j)) continue;
        flooded.set(j);
        component.push_back(j);
        stack.push_back(j);
      }
    }
    if (!leads_out)
      for (int64_t i : component) dead.set(i);
  };
  for (int64_t target : targets) {
    if (cancel.cancelled()) {
      return absl::CancelledError("reconstruction cancelled while connecting inside hard voxels");
    }
    if (!IsInside(grid.at(target))) continue;  // an earlier path reached it
    if (visits_left <= 0) break;
    const VoxelState* s = grid.states().data();
    // Breadth-first search through soft non-outside voxels; parent links give the path.
    parent.Clear();
    queue.clear();
    parent.Insert(target, -1);
    queue.emplace_back(target, 0);
    size_t head = 0;
    int64_t exit = -1;
    bool truncated = false;  // by max_path or kMaxVisited: the search did not see it all
    while (head < queue.size() && exit < 0) {
      if (parent.size() >= kMaxVisited) {
        truncated = true;
        break;
      }
      const auto [i, depth] = queue[head++];
      if (depth >= max_path) {
        truncated = true;
        continue;
      }
      for (int64_t step : steps) {
        const int64_t j = i + step;
        if (IsOutside(s[j]) || IsHard(s[j]) || dead.test(j) || parent.Contains(j)) continue;
        parent.Insert(j, i);
        if (HasOutsideFaceNeighbour(s, j, st)) {
          exit = j;
          break;
        }
        queue.emplace_back(j, depth + 1);
      }
    }
    visits_left -= static_cast<int64_t>(parent.size());
    if (exit < 0) {
      if (!truncated) {
        // Seen whole and no way out: the components it reached are dead.
        parent.ForEachVoxel([&](int64_t i) {
          if (i != target) dead.set(i);
        });
      } else {
        // Cut short: find out once for each component whether it leads out at all.
        for (int64_t step : steps) {
          const int64_t j = target + step;
          if (!IsOutside(s[j]) && !IsHard(s[j]) && !dead.test(j) && !flooded.test(j))
            flood(j);
        }
      }
      continue;
    }
    // Carve from the outside end inwards while each voxel is simple.
    for (int64_t i = exit; i != target; i = parent.Parent(i)) {
      const uint32_t object = NeighbourhoodMask(grid, i, [](VoxelState v) { return !IsOutside(v); });
      if (!IsSimple(object)) break;
      CarveToOutside(grid, i);
      ++stats.carved_voxels;
    }
  }
  // Nothing was carved when there was nothing to reach: no second pass over the grid then.
  stats.inside_hard_after =
      targets.empty() ? 0 : std::count(grid.states().begin(), grid.states().end(), kInsideHard);
  stats.bridge_voxels = BridgeMembraneContacts(grid, threads);
  return stats;
}

namespace {

// Makes the voxels of `path` (at most 3, each face-adjacent to the one before) boundary, in
// order: an inside voxel becomes BOUNDARY, an outside one FROZEN BOUNDARY only when
// (26,6)-simple at its turn and not on the array border. On failure the path is put back as it
// was; on success its voxels are appended to `written` (those it left as they were too).
bool TryBridgePath(VoxelGrid& grid, absl::Span<const int64_t> path,
                   std::vector<int64_t>& written) {
  VoxelState* s = grid.mutable_states().data();
  VoxelState before[3];
  for (size_t k = 0; k < path.size(); ++k) {
    const int64_t v = path[k];
    before[k] = s[v];
    if (IsBoundary(s[v])) continue;
    if (IsInside(s[v])) {
      s[v] |= kBoundaryBit;
      continue;
    }
    const uint32_t object = NeighbourhoodMask(grid, v, [](VoxelState x) { return !IsOutside(x); });
    if (grid.OnArrayBorder(grid.CoordOf(v)) || !IsSimple(object)) {
      for (size_t j = k; j-- > 0;) s[path[j]] = before[j];
      return false;
    }
    s[v] = kBoundaryFrozen;
  }
  written.insert(written.end(), path.begin(), path.end());
  return true;
}

// Tries to join the boundary voxel `centre` to the boundary voxel at `offset` (an edge or
// corner neighbour) by a face path inside their 3x3x3 block: first the shortest ones, one or
// two voxels stepping one axis at a time in each order; then, for an edge neighbour, the
// detours of three voxels that step off the contact's plane along its third axis, cross the
// edge there and step back. A shortest path's voxel can touch a third boundary voxel of the
// block that the contact's two reach only through the rest of the membrane, so that it would
// close a loop and is not simple (a strand of hard voxels hanging by an edge between two
// others); a detour on the strand's other side need not touch it.
bool TryBridge(VoxelGrid& grid, int64_t centre, const int offset[3],
               std::vector<int64_t>& written) {
  static constexpr int kOrders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                        {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  const auto st = grid.strides();
  const int axes = (offset[0] != 0) + (offset[1] != 0) + (offset[2] != 0);
  int64_t path[3];
  for (const auto& order : kOrders) {
    int steps = 0;
    int64_t at = centre;
    for (int k = 0; k < 3; ++k) {
      const int a = order[k];
      if (offset[a] == 0) continue;
      at += offset[a] * st[a];
      if (steps + 1 < axes) path[steps++] = at;
    }
    if (TryBridgePath(grid, absl::MakeConstSpan(path, static_cast<size_t>(steps)), written)) {
      return true;
    }
  }
  if (axes != 2) return false;
  const int off_axis = offset[0] == 0 ? 0 : offset[1] == 0 ? 1 : 2;
  const int a = off_axis == 0 ? 1 : 0;
  const int b = off_axis == 2 ? 1 : 2;
  for (const int side : {-1, 1}) {
    const int64_t out = side * st[off_axis];
    for (const int64_t first : {offset[a] * st[a], offset[b] * st[b]}) {
      const int64_t second = offset[a] * st[a] + offset[b] * st[b] - first;
      path[0] = centre + out;
      path[1] = path[0] + first;
      path[2] = path[1] + second;
      if (TryBridgePath(grid, absl::MakeConstSpan(path, 3), written)) return true;
    }
  }
  return false;
}

// Sets in `plane` every voxel within Chebyshev distance 2 of voxel v (inside the array).
void MarkNear(const VoxelGrid& grid, int64_t v, FlatBitset& plane) {
  const Coord c = grid.CoordOf(v);
  const auto& d = grid.dims();
  for (int z = std::max(c[2] - 2, 0); z <= std::min(c[2] + 2, d[2] - 1); ++z)
    for (int y = std::max(c[1] - 2, 0); y <= std::min(c[1] + 2, d[1] - 1); ++y)
      for (int x = std::max(c[0] - 2, 0); x <= std::min(c[0] + 2, d[0] - 1); ++x)
        plane.set(grid.Index(x, y, z));
}

}  // namespace

int64_t BridgeMembraneContacts(VoxelGrid& grid, int threads) {
  const auto& d = grid.dims();
  const VoxelState* s = grid.states().data();
  // Bridges from boundary voxel i until none is missing or none can be made; the voxels
  // written go to `written`. True when something changed.
  std::vector<int64_t> written;
  auto bridge_from = [&](int64_t i) {
    bool changed = false;
    for (;;) {
      const uint32_t boundary =
          NeighbourhoodMask(grid, i, [](VoxelState v) { return IsBoundary(v); });
      const uint32_t missing = boundary & ~Flood6(kCentreBit, boundary);
      if (missing == 0) break;
      bool bridged = false;
      for (uint32_t m = missing; m != 0 && !bridged; m &= m - 1) {
        const int b = std::countr_zero(m);
        const int offset[3] = {b % 3 - 1, (b / 3) % 3 - 1, b / 9 - 1};
        bridged = TryBridge(grid, i, offset, written);
      }
      if (!bridged) break;
      changed = true;
    }
    return changed;
  };
  // A boundary voxel has something to bridge only when a boundary voxel of its block is not
  // joined to it through the block's boundary voxels. That is read for every boundary voxel
  // first, on the threads (a z plane a task, read only). The first pass visits the voxels
  // read so and those within distance 2 of a voxel written ahead of them in the pass: the
  // outcome at a voxel reads only its 3x3x3 block (and its path voxels' once something is
  // missing), so every other boundary voxel would find nothing missing when a scan of them all
  // reached it. The same voxels are bridged in the same order as by that scan.
  std::vector<std::vector<int64_t>> found(static_cast<size_t>(std::max(d[2] - 2, 0)));
  RunTasks(threads, static_cast<int64_t>(found.size()), [&](int, int64_t task) {
    const int z = static_cast<int>(task) + 1;
    std::vector<int64_t>& out = found[static_cast<size_t>(task)];
    for (int y = 1; y + 1 < d[1]; ++y) {
      const int64_t row = grid.Index(0, y, z);
      for (int x = 1; x + 1 < d[0]; ++x) {
        int64_t i = row + x;
        // Most voxels are not on the boundary: skip them eight at a time.
        if (x + 8 < d[0]) {
          const int skip = FirstBoundaryOfEight(s + i);
          x += skip;
          if (skip == 8) {
            --x;  // the loop's ++x
            continue;
          }
          i += skip;
        } else if (!IsBoundary(s[i])) {
          continue;
        }
        const uint32_t boundary =
            NeighbourhoodMask(grid, i, [](VoxelState v) { return IsBoundary(v); });
        if ((boundary & ~Flood6(kCentreBit, boundary)) != 0) out.push_back(i);
      }
    }
  });
  // Then at most three passes: the first from those voxels, each next one from the voxels
  // within distance 2 of a voxel the pass before wrote (at the end of a voxel's last visit
  // nothing could be bridged there, so elsewhere nothing changes). Writes ahead of the scan
  // are marked in the pass itself; the rest wait for the next pass.
  FlatBitset visit;
  bool any = false;
  for (const std::vector<int64_t>& list : found) any = any || !list.empty();
  if (!any) return 0;  // nothing to bridge: no count of the grid either
  const int64_t before = CountStates(grid.states(), threads).boundary;
  visit.EnsureSize(grid.size());
  for (const std::vector<int64_t>& list : found)
    for (int64_t v : list) visit.set(v);
  found.clear();
  bool changed = true;
  for (int pass = 0; pass < 3 && changed; ++pass) {
    changed = false;
    if (pass > 0) {
      visit.clear_all();
      std::vector<int64_t> last;
      last.swap(written);
      for (int64_t v : last) MarkNear(grid, v, visit);
    }
    uint64_t* vw = visit.words();
    for (int64_t w = 0; w < static_cast<int64_t>(visit.word_count()); ++w) {
      int next_bit = 0;
      while (next_bit < 64) {
        const uint64_t bits = vw[w] & (~0ull << next_bit);  // re-read: marks ahead count
        if (bits == 0) break;
        const int b = std::countr_zero(bits);
        next_bit = b + 1;
        const int64_t i = w * 64 + b;
        if (i >= grid.size()) break;
        const Coord c = grid.CoordOf(i);
        if (c[0] < 1 || c[1] < 1 || c[2] < 1 || c[0] + 1 >= d[0] || c[1] + 1 >= d[1] ||
            c[2] + 1 >= d[2] || !IsBoundary(s[i])) {
          continue;
        }
        const size_t first_new = written.size();
        if (bridge_from(i)) changed = true;
        for (size_t k = first_new; k < written.size(); ++k) MarkNear(grid, written[k], visit);
      }
    }
  }
  return CountStates(grid.states(), threads).boundary - before;
}

}  // namespace membrane

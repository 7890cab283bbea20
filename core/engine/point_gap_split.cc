#include "core/engine/point_gap_split.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>

#include "absl/container/flat_hash_map.h"
#include "absl/status/status.h"
#include "absl/types/span.h"
#include "core/engine/flat_bitset.h"
#include "core/engine/state_planes.h"

namespace membrane {
namespace {

int32_t Find(std::vector<int32_t>& parent, int32_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

// The forward offsets (above 0: each pair once) to the voxels at most `r` apart along each
// axis.
std::vector<int64_t> ForwardOffsets(const VoxelGrid& grid, int r) {
  std::vector<int64_t> offsets;
  const int64_t centre = grid.Index(Coord{r, r, r});
  for (int dz = -r; dz <= r; ++dz)
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx) {
        const int64_t off = grid.Index(Coord{r + dx, r + dy, r + dz}) - centre;
        if (off > 0) offsets.push_back(off);
      }
  return offsets;
}

// The ranks (HardVoxelPoints::voxels) of `sorted`'s voxels, ascending grid indices that all
// hold points: one merge of the two lists.
std::vector<size_t> RanksOf(const HardVoxelPoints& points, const std::vector<int64_t>& sorted) {
  const absl::Span<const int64_t> all = points.voxels();
  std::vector<size_t> ranks(sorted.size());
  size_t r = 0;
  for (size_t k = 0; k < sorted.size(); ++k) {
    while (r < all.size() && all[r] < sorted[k]) ++r;
    ranks[k] = r;
  }
  return ranks;
}

// Whether the points of `sorted`'s voxels k and c come within `reach` (false when one holds
// none, as a hard voxel made by no point would).
bool Near(const HardVoxelPoints& points, const std::vector<int64_t>& sorted,
          const std::vector<size_t>& ranks, size_t k, size_t c, double reach) {
  const absl::Span<const int64_t> all = points.voxels();
  if (ranks[k] >= all.size() || all[ranks[k]] != sorted[k]) return false;
  if (ranks[c] >= all.size() || all[ranks[c]] != sorted[c]) return false;
  return points.PointsWithin(ranks[k], ranks[c], reach);
}

// Joins the voxels of `sorted` (ascending grid indices) that lie `offsets` apart and whose
// points come within `reach`. Each offset's partner is found by a cursor that only moves
// forward, as the voxels do: no search.
void JoinAlong(const VoxelGrid& grid, const HardVoxelPoints& points,
               const std::vector<int64_t>& sorted, const std::vector<size_t>& ranks,
               const std::vector<int64_t>& offsets, double reach, std::vector<int32_t>& parent) {
  const VoxelState* s = grid.states().data();
  const int64_t voxels = grid.size();
  std::vector<size_t> cursor(offsets.size(), 0);
  for (size_t k = 0; k < sorted.size(); ++k) {
    const int64_t v = sorted[k];
    for (size_t o = 0; o < offsets.size(); ++o) {
      const int64_t n = v + offsets[o];
      if (n >= voxels || !IsHard(s[n])) continue;
      size_t& c = cursor[o];
      while (c < sorted.size() && sorted[c] < n) ++c;
      if (c == sorted.size() || sorted[c] != n) continue;
      const int32_t a = Find(parent, static_cast<int32_t>(k));
      const int32_t b = Find(parent, static_cast<int32_t>(c));
      if (a == b || !Near(points, sorted, ranks, k, c, reach)) continue;
      parent[a] = b;
    }
  }
}

// Joins the voxels of `sorted` outside the largest class of `parent` to every voxel of
// `sorted` `offsets` apart, before or after, whose points come within `reach`: every pair
// with a voxel outside that class is read, and the pairs inside it are joined already, so the
// classes come out as from every pair, at the cost of the voxels outside the largest class.
void JoinOutsideLargest(const VoxelGrid& grid, const HardVoxelPoints& points,
                        const std::vector<int64_t>& sorted, const std::vector<size_t>& ranks,
                        const std::vector<int64_t>& offsets, double reach,
                        const std::vector<int64_t>& size, std::vector<int32_t>& parent) {
  const int32_t largest = static_cast<int32_t>(std::max_element(size.begin(), size.end()) -
                                               size.begin());
  std::vector<int32_t> others;
  for (size_t k = 0; k < sorted.size(); ++k)
    if (Find(parent, static_cast<int32_t>(k)) != largest) others.push_back(static_cast<int32_t>(k));
  const VoxelState* s = grid.states().data();
  const int64_t voxels = grid.size();
  for (int32_t k : others) {
    const int64_t v = sorted[static_cast<size_t>(k)];
    for (int64_t off : offsets)
      for (int64_t n : {v - off, v + off}) {
        if (n < 0 || n >= voxels || !IsHard(s[n])) continue;
        const auto it = std::lower_bound(sorted.begin(), sorted.end(), n);
        if (it == sorted.end() || *it != n) continue;
        const size_t c = static_cast<size_t>(it - sorted.begin());
        const int32_t a = Find(parent, k);
        const int32_t b = Find(parent, static_cast<int32_t>(c));
        if (a == b || !Near(points, sorted, ranks, static_cast<size_t>(k), c, reach)) continue;
        parent[a] = b;
      }
  }
}

// The number of classes of `parent` holding at least `min_voxels`; `size` gets each root's
// class size (0 for the others).
int BigClasses(std::vector<int32_t>& parent, int64_t min_voxels, std::vector<int64_t>& size) {
  size.assign(parent.size(), 0);
  for (size_t k = 0; k < parent.size(); ++k) ++size[Find(parent, static_cast<int32_t>(k))];
  int big = 0;
  for (size_t k = 0; k < parent.size(); ++k)
    big += parent[k] == static_cast<int32_t>(k) && size[k] >= min_voxels;
  return big;
}

constexpr int64_t kCancelPoll = 1 << 16;

// The hard voxels of `grid`, ascending; false when `cancel` fired. Hard voxels are a few
// per thousand of the grid: the states are tested 64 at a time into the words of a block's
// bit-plane, and only the set bits are read.
bool ListHardVoxels(const VoxelGrid& grid, const CancelToken& cancel, std::vector<int64_t>& hard) {
  const absl::Span<const VoxelState> states(grid.states());
  constexpr int64_t kBlock = int64_t{1} << 20;
  FlatBitset plane;
  for (int64_t begin = 0; begin < grid.size(); begin += kBlock) {
    if (cancel.cancelled()) return false;
    const int64_t length = std::min(kBlock, grid.size() - begin);
    plane.EnsureSize(length);
    FillStatePlane(states.subspan(static_cast<size_t>(begin), static_cast<size_t>(length)),
                   StatePredicate::kHard, plane, 0, static_cast<int64_t>(plane.word_count()));
    const uint64_t* words = plane.words();
    for (size_t w = 0; w < plane.word_count(); ++w)
      for (uint64_t bits = words[w]; bits != 0; bits &= bits - 1)
        hard.push_back(begin + static_cast<int64_t>(w) * 64 + std::countr_zero(bits));
  }
  return true;
}

// The voxels of `grid` 26-connected to voxel `start` through hard voxels, breadth first in
// the grid's neighbour order (`seen` marks them).
std::vector<int64_t> BreadthFirst(const VoxelGrid& grid, int64_t start, FlatBitset& seen) {
  const VoxelState* s = grid.states().data();
  std::vector<int64_t> component(1, start);
  seen.set(start);
  for (size_t k = 0; k < component.size(); ++k)
    for (int64_t off : grid.neighbour_offsets()) {
      const int64_t n = component[k] + off;
      if (IsHard(s[n]) && !seen.test(n)) {
        seen.set(n);
        component.push_back(n);
      }
    }
  return component;
}

// The position of voxel `v` in `sorted`, which holds it.
size_t PositionOf(const std::vector<int64_t>& sorted, int64_t v) {
  return static_cast<size_t>(std::lower_bound(sorted.begin(), sorted.end(), v) - sorted.begin());
}

// Joins the voxels of `hard` (ascending grid indices) that lie `offsets` apart when
// near(k, c) holds for their positions k < c; false when `cancel` fired. Each offset's partner
// is found by a cursor through `hard` that only moves forward, as the voxels do: the grid's
// states are not read (a state byte a plane ahead is a cache miss per voxel; the cursors
// stream).
template <typename Near>
bool JoinNeighbours(const std::vector<int64_t>& hard, const std::vector<int64_t>& offsets,
                    const CancelToken& cancel, std::vector<int32_t>& parent, Near near) {
  const size_t n = hard.size();
  std::vector<size_t> cursor(offsets.size(), 0);
  for (size_t k = 0; k < n; ++k) {
    if (k % kCancelPoll == 0 && cancel.cancelled()) return false;
    const int64_t v = hard[k];
    for (size_t o = 0; o < offsets.size(); ++o) {
      const int64_t m = v + offsets[o];
      size_t& c = cursor[o];
      while (c < n && hard[c] < m) ++c;
      if (c == n || hard[c] != m) continue;
      const int32_t a = Find(parent, static_cast<int32_t>(k));
      const int32_t b = Find(parent, static_cast<int32_t>(c));
      if (a == b || !near(k, c)) continue;
      parent[a] = b;
    }
  }
  return true;
}

}  // namespace

std::vector<std::vector<int64_t>> SplitAtPointGaps(const VoxelGrid& grid,
                                                   const HardVoxelPoints& points,
                                                   const std::vector<int64_t>& component,
                                                   double reach, int64_t min_voxels) {
  std::vector<int64_t> sorted = component;
  std::sort(sorted.begin(), sorted.end());
  std::vector<int32_t> parent(sorted.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<int64_t> size;
  // The 26-neighbours join almost every surface; the wider pairs are read only when that
  // leaves two big parts, and only around the voxels outside the largest. Points within
  // `reach` lie in voxels at most ceil(reach) apart along each axis.
  const std::vector<size_t> ranks = RanksOf(points, sorted);
  JoinAlong(grid, points, sorted, ranks, ForwardOffsets(grid, 1), reach, parent);
  if (BigClasses(parent, min_voxels, size) < 2) return {component};
  const int r = static_cast<int>(std::ceil(reach));
  if (r > 1) {
    JoinOutsideLargest(grid, points, sorted, ranks, ForwardOffsets(grid, r), reach, size,
                       parent);
  }
  if (BigClasses(parent, min_voxels, size) < 2) return {component};
  // The big parts, numbered in the order their first voxel comes in the component.
  std::vector<int32_t> part_of_root(sorted.size(), -1);
  int32_t parts = 0;
  std::vector<int32_t> part_of_voxel(component.size());
  for (size_t k = 0; k < component.size(); ++k) {
    const size_t at = static_cast<size_t>(
        std::lower_bound(sorted.begin(), sorted.end(), component[k]) - sorted.begin());
    const int32_t root = Find(parent, static_cast<int32_t>(at));
    if (size[root] >= min_voxels && part_of_root[root] < 0) part_of_root[root] = parts++;
    part_of_voxel[k] = part_of_root[root];
  }
  std::vector<std::vector<int64_t>> out(static_cast<size_t>(parts));
  for (size_t k = 0; k < component.size(); ++k)
    if (part_of_voxel[k] >= 0) out[static_cast<size_t>(part_of_voxel[k])].push_back(component[k]);
  return out;
}

absl::StatusOr<DataPieces> FindDataPieces(const VoxelGrid& grid, const HardVoxelPoints* points,
                                          double reach, double min_fraction,
                                          const CancelToken& cancel) {
  auto cancelled = [] { return absl::CancelledError("reconstruction cancelled"); };
  std::vector<int64_t> hard;
  if (!ListHardVoxels(grid, cancel, hard)) return cancelled();
  if (hard.size() >= static_cast<size_t>(std::numeric_limits<int32_t>::max())) {
    return absl::ResourceExhaustedError("over 2^31 hard voxels: too many to tell pieces apart");
  }
  DataPieces out;
  const size_t n = hard.size();
  if (n == 0) return out;
  out.min_voxels = static_cast<int64_t>(
      std::ceil(std::max(1.0, min_fraction * static_cast<double>(n))));
  const bool by_points = points != nullptr && reach > 0;
  const std::vector<size_t> ranks = by_points ? RanksOf(*points, hard) : std::vector<size_t>();
  const std::vector<int64_t> offsets = ForwardOffsets(grid, 1);

  // The classes of SplitAtPointGaps's 26-neighbour step over all hard voxels at once (its
  // pairs never leave a component; the classes, not the roots, decide what it returns), or
  // the components themselves without points.
  std::vector<int32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto near = [&](size_t k, size_t c) { return Near(*points, hard, ranks, k, c, reach); };
  bool done = by_points
                  ? JoinNeighbours(hard, offsets, cancel, parent, near)
                  : JoinNeighbours(hard, offsets, cancel, parent, [](size_t, size_t) { return true; });
  if (!done) return cancelled();
  std::vector<int64_t> size(n, 0);
  for (size_t k = 0; k < n; ++k) ++size[Find(parent, static_cast<int32_t>(k))];
  // One class holding all but fewer than min_voxels of the hard voxels: no other class, and
  // no component without it, can be a piece, and its component is not split.
  const int64_t largest = *std::max_element(size.begin(), size.end());
  if (static_cast<int64_t>(n) - largest < out.min_voxels && largest >= out.min_voxels) {
    out.count = 1;
    return out;
  }

  // Each voxel's 26-component, numbered in the order of their least voxels.
  std::vector<int32_t> label(n);
  std::vector<int64_t> component_size;
  std::vector<int64_t> component_start;  // its least voxel
  {
    std::vector<int32_t> joined;
    if (by_points) {
      joined.resize(n);
      std::iota(joined.begin(), joined.end(), 0);
      if (!JoinNeighbours(hard, offsets, cancel, joined, [](size_t, size_t) { return true; })) {
        return cancelled();
      }
    }
    std::vector<int32_t>& components = by_points ? joined : parent;
    std::vector<int32_t> label_of_root(n, -1);
    for (size_t k = 0; k < n; ++k) {
      const int32_t r = Find(components, static_cast<int32_t>(k));
      if (label_of_root[r] < 0) {
        label_of_root[r] = static_cast<int32_t>(component_size.size());
        component_size.push_back(0);
        component_start.push_back(hard[k]);
      }
      label[k] = label_of_root[r];
      ++component_size[static_cast<size_t>(label[k])];
    }
  }
  const size_t components = component_size.size();

  // A component's classes: split where two hold min_voxels each (SplitAtPointGaps's test),
  // the wider pairs read then around the voxels outside its largest class.
  std::vector<bool> split(components, false);
  if (by_points) {
    std::vector<int> big(components, 0);
    for (size_t k = 0; k < n; ++k)
      big[label[k]] += parent[k] == static_cast<int32_t>(k) && size[k] >= out.min_voxels;
    const int r = static_cast<int>(std::ceil(reach));
    for (size_t c = 0; c < components; ++c) {
      if (component_size[c] < out.min_voxels || big[c] < 2) continue;
      if (r > 1) {
        std::vector<int32_t> at;  // the component's voxels: positions in `hard`, ascending
        for (size_t k = 0; k < n; ++k)
          if (label[k] == static_cast<int32_t>(c)) at.push_back(static_cast<int32_t>(k));
        int32_t largest_root = at.front();
        for (int32_t k : at)
          if (parent[k] == k && size[k] > size[largest_root]) largest_root = k;
        std::vector<int32_t> others;
        for (int32_t k : at)
          if (Find(parent, k) != largest_root) others.push_back(k);
        const VoxelState* s = grid.states().data();
        const int64_t voxels = grid.size();
        const std::vector<int64_t> wide = ForwardOffsets(grid, r);
        for (int32_t k : others) {
          if (cancel.cancelled()) return cancelled();
          const int64_t v = hard[static_cast<size_t>(k)];
          for (int64_t off : wide)
            for (int64_t m : {v - off, v + off}) {
              if (m < 0 || m >= voxels || !IsHard(s[m])) continue;
              const size_t p = PositionOf(hard, m);
              if (label[p] != static_cast<int32_t>(c)) continue;
              const int32_t a = Find(parent, k);
              const int32_t b = Find(parent, static_cast<int32_t>(p));
              if (a == b || !near(static_cast<size_t>(k), p)) continue;
              parent[a] = b;
            }
        }
        for (int32_t k : at) size[k] = 0;
        for (int32_t k : at) ++size[Find(parent, k)];
        big[c] = 0;
        for (int32_t k : at) big[c] += parent[k] == k && size[k] >= out.min_voxels;
      }
      split[c] = big[c] >= 2;
      out.split = out.split || split[c];
    }
  }

  // Two pieces or more: each in its component's breadth-first order, a split component's
  // big classes numbered in the order their first voxel comes in it.
  for (size_t c = 0; c < components; ++c)
    if (component_size[c] >= out.min_voxels) out.count += split[c] ? 2 : 1;
  if (out.count < 2) return out;
  out.count = 0;
  FlatBitset seen(grid.size());
  for (size_t c = 0; c < components; ++c) {
    if (component_size[c] < out.min_voxels) continue;
    if (cancel.cancelled()) return cancelled();
    std::vector<int64_t> component = BreadthFirst(grid, component_start[c], seen);
    if (!split[c]) {
      out.pieces.push_back(std::move(component));
      continue;
    }
    absl::flat_hash_map<int32_t, size_t> part;
    for (int64_t v : component) {
      const int32_t root = Find(parent, static_cast<int32_t>(PositionOf(hard, v)));
      if (size[root] < out.min_voxels) continue;
      auto [it, added] = part.emplace(root, out.pieces.size());
      if (added) out.pieces.emplace_back();
      out.pieces[it->second].push_back(v);
    }
  }
  out.count = static_cast<int>(out.pieces.size());
  return out;
}

}  // namespace membrane

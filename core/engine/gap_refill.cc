#include "core/engine/gap_refill.h"

#include <algorithm>
#include <array>
#include <deque>
#include <limits>
#include <vector>

#include "absl/container/flat_hash_set.h"
#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "core/engine/local_topology.h"
#include "core/engine/state_planes.h"

namespace membrane {
namespace {

constexpr int64_t kCancelPoll = 1 << 16;

// Per axis, per grid row along it: the lowest and highest coordinate of a hard voxel on the
// row (lowest > highest when none). Row of voxel (x, y, z): axis 0 y + ny z, axis 1 x + nx z,
// axis 2 x + nx y.
class HardRowExtremes {
 public:
  explicit HardRowExtremes(const VoxelGrid& grid) : dims_(grid.dims()) {
    const int nx = dims_[0], ny = dims_[1], nz = dims_[2];
    const int32_t none_lo = std::numeric_limits<int32_t>::max(), none_hi = -1;
    rows_[0] = static_cast<size_t>(ny) * nz;
    rows_[1] = static_cast<size_t>(nx) * nz;
    rows_[2] = static_cast<size_t>(nx) * ny;
    for (int d = 0; d < 3; ++d) {
      lo_[d].assign(rows_[d], none_lo);
      hi_[d].assign(rows_[d], none_hi);
    }
    // Every voxel of the grid is read, hard ones are few: eight at a time where none is.
    const VoxelState* s = grid.states().data();
    int64_t i = 0;
    for (int z = 0; z < nz; ++z)
      for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx;) {
          if (x + 8 <= nx && NoHardOfEight(s + i)) {
            x += 8;
            i += 8;
            continue;
          }
          if (IsHard(s[i])) {
            Note(0, RowOf(0, x, y, z), x);
            Note(1, RowOf(1, x, y, z), y);
            Note(2, RowOf(2, x, y, z), z);
          }
          ++x;
          ++i;
        }
  }

  // True when the row of voxel c along axis d holds a hard voxel past coordinate t on the
  // side `sign`.
  bool HardPast(int d, const Coord& c, int t, int sign) const {
    const size_t row = RowOf(d, c.x, c.y, c.z);
    return sign > 0 ? hi_[d][row] > t : lo_[d][row] < t;
  }

 private:
  size_t RowOf(int d, int x, int y, int z) const {
    if (d == 0) return y + static_cast<size_t>(dims_[1]) * z;
    if (d == 1) return x + static_cast<size_t>(dims_[0]) * z;
    return x + static_cast<size_t>(dims_[0]) * y;
  }
  void Note(int d, size_t row, int t) {
    lo_[d][row] = std::min(lo_[d][row], t);
    hi_[d][row] = std::max(hi_[d][row], t);
  }

  std::array<int, 3> dims_;
  std::array<size_t, 3> rows_;
  std::array<std::vector<int32_t>, 3> lo_, hi_;
};

// Of the 6 axis rays from an outside voxel: those that meet a gap wall (the first non-outside
// voxel on the ray and the one after it are both soft or frozen: the ray enters the solid where
// it holds no data, and a hard voxel lies further on: the solid's far side), and those that
// leave through the outside to the array's border (the way out). A ray that meets the data
// first looks at a scanned wall from outside it.
struct RayCounts {
  int gap_walls = 0;
  int open = 0;
};

RayCounts CountRays(const VoxelGrid& grid, const HardRowExtremes& rows, int64_t v) {
  const Coord c = grid.CoordOf(v);
  const int at[3] = {c.x, c.y, c.z};
  const auto st = grid.strides();
  RayCounts count;
  for (int d = 0; d < 3; ++d)
    for (int sign = -1; sign <= 1; sign += 2) {
      int t = at[d] + sign;
      int64_t u = v + sign * st[d];
      while (t > 0 && t < grid.dim(d) - 1 && IsOutside(grid.at(u))) {
        t += sign;
        u += sign * st[d];
      }
      if (t <= 0 || t >= grid.dim(d) - 1 || IsOutside(grid.at(u))) {
        ++count.open;
        continue;
      }
      if (IsHard(grid.at(u))) continue;
      const VoxelState next = grid.at(u + sign * st[d]);
      if (IsOutside(next) || IsHard(next)) continue;
      count.gap_walls += rows.HardPast(d, c, t + sign, sign);
    }
  return count;
}

// No hard voxel within Chebyshev distance r of c (voxels past the array count as none).
bool InGap(const VoxelGrid& grid, const Coord& c, int r) {
  const auto& d = grid.dims();
  for (int z = std::max(c.z - r, 0); z <= std::min(c.z + r, d[2] - 1); ++z)
    for (int y = std::max(c.y - r, 0); y <= std::min(c.y + r, d[1] - 1); ++y) {
      const int64_t row = grid.Index(0, y, z);
      for (int x = std::max(c.x - r, 0); x <= std::min(c.x + r, d[0] - 1); ++x)
        if (IsHard(grid.at(row + x))) return false;
    }
  return true;
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
                                                 const CancelToken& cancel) {
  if (options.gap_radius < 1 || options.gap_radius > 16 || options.min_enclosed_rays < 1 ||
      options.min_enclosed_rays > 6 || options.max_open_rays < 0 || options.max_open_rays > 6) {
    return absl::InvalidArgumentError(absl::StrCat(
        "gap refill options out of range: gap_radius ", options.gap_radius,
        " (1..16), min_enclosed_rays ", options.min_enclosed_rays, " (1..6), max_open_rays ",
        options.max_open_rays, " (0..6)"));
  }
  GapRefillStats stats;
  if (!options.enabled) return stats;
  const HardRowExtremes rays(grid);
  // The region to refill is read on the membrane as the shrink left it (the fill itself
  // changes what the rays meet): the outside voxels in a gap and behind gap walls, reached
  // from the membrane through such voxels.
  auto in_region = [&](int64_t v) {
    if (!IsOutside(grid.at(v)) || grid.OnArrayBorder(grid.CoordOf(v))) return false;
    if (!InGap(grid, grid.CoordOf(v), options.gap_radius)) return false;
    const RayCounts count = CountRays(grid, rays, v);
    return count.gap_walls >= options.min_enclosed_rays && count.open <= options.max_open_rays;
  };
  absl::flat_hash_set<int64_t> region, rejected;
  std::vector<int64_t> frontier;
  // Seeds in voxel order, off the array border. This loop reads the whole grid, mostly
  // outside voxels by now: it walks rows (no division for the border test) and steps over
  // eight voxels whose face neighbours are all outside with six word loads.
  const auto& dims = grid.dims();
  const auto st = grid.strides();
  const VoxelState* states = grid.states().data();
  auto outside_around_eight = [&](int64_t v) {
    return AllOutsideOfEight(states + v - 1) && AllOutsideOfEight(states + v + 1) &&
           AllOutsideOfEight(states + v - st[1]) && AllOutsideOfEight(states + v + st[1]) &&
           AllOutsideOfEight(states + v - st[2]) && AllOutsideOfEight(states + v + st[2]);
  };
  for (int z = 1; z < dims[2] - 1; ++z) {
    for (int y = 1; y < dims[1] - 1; ++y) {
      if (cancel.cancelled()) return absl::CancelledError("gap refill cancelled");
      const int64_t row = grid.Index(0, y, z);
      const int64_t end = row + dims[0] - 1;
      for (int64_t v = row + 1; v < end;) {
        if (v + 8 <= end && outside_around_eight(v)) {
          v += 8;
          continue;
        }
        if (IsOutside(states[v]) && HasSolidFaceNeighbour(grid, v) && in_region(v)) {
          region.insert(v);
          frontier.push_back(v);
        }
        ++v;
      }
    }
  }
  const std::vector<int64_t> seeds = frontier;
  while (!frontier.empty()) {
    if (cancel.cancelled()) return absl::CancelledError("gap refill cancelled");
    const int64_t v = frontier.back();
    frontier.pop_back();
    for (int d = 0; d < 3; ++d)
      for (int64_t u : {v - st[d], v + st[d]}) {
        if (region.contains(u) || rejected.contains(u)) continue;
        if (in_region(u)) {
          region.insert(u);
          frontier.push_back(u);
        } else {
          rejected.insert(u);
        }
      }
  }
  rejected.clear();
  // Fill from the membrane inwards, each voxel when it is beside the solid and simple; a
  // voxel not simple yet is tried again when a neighbour joins the solid.
  std::deque<int64_t> queue(seeds.begin(), seeds.end());
  std::vector<int64_t> touched;
  int64_t steps = 0;
  while (!queue.empty()) {
    if (++steps % kCancelPoll == 0 && cancel.cancelled()) break;
    const int64_t v = queue.front();
    queue.pop_front();
    if (!IsOutside(grid.at(v)) || !HasSolidFaceNeighbour(grid, v)) continue;
    const uint32_t object = NeighbourhoodMask(grid, v, [](VoxelState x) { return !IsOutside(x); });
    if (!IsSimple(object)) continue;
    grid.set(v, kInsideSoft);
    ++stats.refilled_voxels;
    touched.push_back(v);
    for (int64_t off : grid.neighbour_offsets())
      if (IsOutside(grid.at(v + off)) && region.contains(v + off)) queue.push_back(v + off);
  }
  // Settle the positions of the refilled voxels and of the solid around them.
  for (int64_t v : touched) {
    grid.set(v, Settled(grid, v));
    for (int64_t off : grid.neighbour_offsets())
      if (!IsOutside(grid.at(v + off))) grid.set(v + off, Settled(grid, v + off));
  }
  if (cancel.cancelled()) return absl::CancelledError("gap refill cancelled");
  return stats;
}

}  // namespace membrane

#include "core/engine/hole_opening.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include "core/base/parallel_tasks.h"
#include "core/engine/incursion_test.h"
#include "core/engine/plug_wall_core.h"
#include "core/engine/post_process.h"
#include "core/engine/voxel_state_words.h"
#include "core/engine/voxel_topology.h"
#include "core/geometry/vec3.h"

namespace membrane {
namespace {

// The 26 lattice directions (each of the 13 lines in both senses).
constexpr std::array<Coord, 26> kDirections = [] {
  std::array<Coord, 26> dirs{};
  int n = 0;
  for (int z = -1; z <= 1; ++z)
    for (int y = -1; y <= 1; ++y)
      for (int x = -1; x <= 1; ++x)
        if (x != 0 || y != 0 || z != 0) dirs[n++] = {x, y, z};
  return dirs;
}();

// Zero when two lattice directions are perpendicular.
int CoordDot(const Coord& a, const Coord& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

Vec3d ToVec3d(const Coord& c) { return {double(c.x), double(c.y), double(c.z)}; }

// What a carve must keep (shells, cavities) and change (the summed genus, by one).
struct TopologyCounts {
  int shells = 0, cavities = 0, genus = 0;
};

TopologyCounts Counts(const VoxelTopology& t) {
  return {t.shells, t.cavities, TotalGenus(t)};
}

// One plug: the non-hard voxels of a 6-step staircase from `path[0]` along `dir`, with the
// outside voxels `before` (behind path[0]) and `after` (past the last) at its two ends.
struct Plug {
  Coord dir;
  std::vector<int64_t> path;
  int64_t before = 0, after = 0;
};

class PlugFinder {
 public:
  PlugFinder(const VoxelGrid& grid, const HoleOpeningOptions& o, const HardVoxelPoints& points)
      : grid_(grid), o_(o), points_(points), s_(grid.states().data()), st_(grid.strides()) {}

  // The staircase from boundary voxel i along dir, when the voxel behind it is outside and it
  // reaches the outside through at most max_plug non-hard voxels.
  bool Walk(int64_t i, const Coord& dir, Plug& plug) const {
    int axes[3], m = 0;
    for (int a = 0; a < 3; ++a)
      if (dir[a] != 0) axes[m++] = a;
    auto step = [&](int j) { return dir[axes[j % m]] * st_[axes[j % m]]; };
    plug.dir = dir;
    plug.before = i - step(m - 1);
    if (!IsOutside(s_[plug.before])) return false;
    plug.path.assign(1, i);
    Coord c = grid_.CoordOf(i);
    int64_t w = i;
    for (int j = 0;; ++j) {
      w += step(j);
      c[axes[j % m]] += dir[axes[j % m]];
      if (grid_.OnArrayBorder(c) || IsHard(s_[w])) return false;
      if (IsOutside(s_[w])) break;
      if (static_cast<int>(plug.path.size()) >= o_.max_plug) return false;
      plug.path.push_back(w);
    }
    plug.after = w;
    return true;
  }

  // The tests of HoleOpeningOptions but the join and the topology, cheapest first. A passage
  // lined with data stands in for the facing test and lets the clear line run off the voxel
  // centres: both read a hole narrower than a plane fit's 3x3x3 voxels.
  bool Surrounded(const Plug& plug) const {
    const int64_t mid = plug.path[(plug.path.size() - 1) / 2];
    std::array<Coord, 8> hits;
    int data = 0, farthest = 0;
    if (!RaysMeetData(plug.dir, mid, hits, data, farthest) ||
        std::popcount(Sectors(plug.dir, mid, 0, 3)) < o_.min_sectors) {
      return false;
    }
    std::optional<bool> lined;
    auto passage = [&] {
      if (!lined) lined = DataAlongPassage(plug.dir, mid);
      return *lined;
    };
    // Only a waist whose walls every ray meets within narrow_steps can be narrower than the
    // plane fit.
    const bool narrow = farthest <= o_.narrow_steps;
    const int facing = HitsFacingPlug(plug.dir, hits, data);
    if (facing < data && (!narrow || facing < o_.passage_facing_hits || !passage())) {
      return false;
    }
    return Clear(plug, 1) || (o_.clearance_samples > 1 && narrow && passage() &&
                              Clear(plug, o_.clearance_samples));
  }

 private:
  // Rays across the plug: none reaches the outside and enough meet data (`hits`, `data` of
  // them, the farthest `farthest` steps from the middle voxel).
  bool RaysMeetData(const Coord& dir, int64_t mid, std::array<Coord, 8>& hits, int& data,
                    int& farthest) const {
    data = 0;
    farthest = 0;
    for (const Coord& e : kDirections) {
      if (CoordDot(e, dir) != 0) continue;
      const int64_t rs = e.x * st_[0] + e.y * st_[1] + e.z * st_[2];
      Coord c = grid_.CoordOf(mid);
      int64_t q = mid;
      for (int t = 1; t <= o_.ring_radius; ++t) {
        q += rs;
        c = {c.x + e.x, c.y + e.y, c.z + e.z};
        if (grid_.OnArrayBorder(c) || IsOutside(s_[q])) return false;
        if (IsHard(s_[q])) {
          hits[data++] = c;
          farthest = std::max(farthest, t);
          break;
        }
        // Into the solid's interior: enclosed, not open.
        if (IsInside(s_[q])) break;
      }
    }
    return data >= o_.min_data_rays;
  }

  // How many of the hard voxels met face the plug (the hole's walls, not a wall with a data
  // hole, whose points face along the plug).
  int HitsFacingPlug(const Coord& dir, const std::array<Coord, 8>& hits, int data) const {
    const Vec3d along = ToVec3d(dir);
    const double len = Norm(along);
    int facing = 0;
    for (int k = 0; k < data; ++k) {
      const Coord& c = hits[k];
      Vec3d n;
      if (points_.PlaneNormal(grid_, {c.x - 1, c.y - 1, c.z - 1}, {c.x + 1, c.y + 1, c.z + 1},
                              n) &&
          std::abs(Dot(n, along)) / len < o_.max_facing_cos) {
        ++facing;
      }
    }
    return facing;
  }

  // A passage lined with data: the sectors around the staircase's line that hold hard voxels
  // both before and after the middle voxel (passage_from to passage_to voxels along the line,
  // either way) number at least passage_sectors. A scanned wall with a data hole holds its
  // ring in one layer across the passage (tilted, its two halves on opposite sides); a hole
  // whose walls curve at the voxel's scale (a waist 2.4 voxels wide: the points' planes in
  // 3x3x3 voxels follow the funnel, not the wall) has data along it on both sides.
  bool DataAlongPassage(const Coord& dir, int64_t mid) const {
    return std::popcount(Sectors(dir, mid, o_.passage_from, o_.passage_to) &
                         Sectors(dir, mid, -o_.passage_to, -o_.passage_from)) >=
           o_.passage_sectors;
  }

  // The angular sectors (bit k: the k-th eighth of a turn) around the staircase's line that
  // hold hard voxels within ring_radius - 1 of the middle voxel whose offset along the line
  // lies in [from, to] (from 0: in [-to, to]).
  unsigned Sectors(const Coord& dir, int64_t mid, double from, double to) const {
    const Vec3d along = ToVec3d(dir);
    const double len = Norm(along);
    const Vec3d d = {along[0] / len, along[1] / len, along[2] / len};
    // An orthonormal pair (u, v) across d.
    Vec3d u = std::abs(d[0]) > 0.6 ? Vec3d{0, 1, 0} : Vec3d{1, 0, 0};
    u = u - Dot(u, d) * d;
    const double ul = Norm(u);
    u = {u[0] / ul, u[1] / ul, u[2] / ul};
    const Vec3d v = Cross(d, u);
    const int r = o_.ring_radius - 1;
    const Coord c = grid_.CoordOf(mid);
    unsigned sectors = 0;
    for (int z = -r; z <= r; ++z)
      for (int y = -r; y <= r; ++y)
        for (int x = -r; x <= r; ++x) {
          const Coord q{c.x + x, c.y + y, c.z + z};
          if (!grid_.Contains(q) || !IsHard(s_[grid_.Index(q)])) continue;
          const Vec3d p = {double(x), double(y), double(z)};
          const double at = Dot(p, d);
          if (from == 0 ? std::abs(at) > to : at < from || at > to) continue;
          const double pu = Dot(p, u), pv = Dot(p, v);
          const double radial = std::hypot(pu, pv);
          if (radial < 0.5 || radial > r) continue;
          const double turn = (std::atan2(pv, pu) + std::numbers::pi) / (2 * std::numbers::pi);
          sectors |= 1u << (static_cast<int>(turn * 8) & 7);
        }
    return sectors;
  }

  // A line parallel to the staircase, through the same spot of every plug voxel (of a
  // samples^3 subdivision), at least min_clearance from the points.
  bool Clear(const Plug& plug, int samples) const {
    const int radius = static_cast<int>(std::ceil(o_.min_clearance));
    std::vector<bool> open(static_cast<size_t>(samples) * samples * samples, true);
    std::vector<double> distances;
    for (int64_t p : plug.path) {
      points_.SpotDistances(grid_, grid_.CoordOf(p), radius, samples, distances);
      bool any = false;
      for (size_t n = 0; n < open.size(); ++n) {
        open[n] = open[n] && distances[n] >= o_.min_clearance;
        any = any || open[n];
      }
      if (!any) return false;
    }
    return true;
  }

  const VoxelGrid& grid_;
  const HoleOpeningOptions& o_;
  const HardVoxelPoints& points_;
  const VoxelState* s_;
  const std::array<int64_t, 3> st_;
};

}  // namespace

absl::StatusOr<HoleOpeningStats> OpenPluggedHoles(VoxelGrid& grid,
                                                  const HoleOpeningOptions& options,
                                                  const HardVoxelPoints* points,
                                                  const CancelToken& cancel, int threads) {
  HoleOpeningStats stats;
  if (!options.enabled || points == nullptr) return stats;
  const auto start = std::chrono::steady_clock::now();
  auto done = [&] {
    stats.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return stats;
  };
  const PlugFinder finder(grid, options, *points);
  VoxelState* s = grid.mutable_states().data();
  // Counted over the grid at the first plug that passes every test, then kept by the changes.
  std::optional<TopologyCounts> topology;
  std::vector<std::pair<int64_t, VoxelState>> undo;
  Plug plug;
  // The plugs from boundary voxel i, in direction order; false when max_openings is reached.
  const auto visit = [&](int64_t i) {
    for (const Coord& dir : kDirections) {
      if (stats.opened + stats.refused >= options.max_openings) return false;
      if (!finder.Walk(i, dir, plug) || !finder.Surrounded(plug)) continue;
      const int64_t mid = plug.path[(plug.path.size() - 1) / 2];
      if ((options.wall_core_depth > 0 &&
           PlugInsideWallCore(grid, mid, plug.dir, options.ring_radius,
                              options.wall_core_depth)) ||
          (options.wall_faces_spread > 0 &&
           PlugBetweenWallFaces(grid, *points, mid, plug.dir, options.ring_radius,
                                options.narrow_steps, options.wall_faces_spread))) {
        ++stats.wall_cores;
        continue;
      }
      if (OutsideJoinedInCube(grid, mid, plug.before, plug.after, options.join_radius))
        continue;
      if (!topology) topology = Counts(ComputeVoxelTopology(grid));
      // Counted around the plug, in the join test's cube: the same answer as the whole
      // grid's count (a carve changes chi only at its own corners; with no cavities, a plug
      // open to the outside makes none), which is taken only when the plug's shell is not
      // known to stay one inside the cube.
      const CarveTopologyChange local = CountCarveLocally(grid, plug.path, options.join_radius);
      undo.clear();
      for (int64_t p : plug.path)
        for (int64_t offset : grid.block_offsets()) undo.emplace_back(p + offset, s[p + offset]);
      for (int64_t p : plug.path) CarveToOutside(grid, p);
      TopologyCounts after = *topology;
      if (local.shells == CarveTopologyChange::Shells::kRemoved) {
        --after.shells;
      } else if (local.shells == CarveTopologyChange::Shells::kKept && topology->cavities == 0 &&
                 local.touches_outside) {
        after.genus -= local.euler_change;
      } else {
        after = Counts(ComputeVoxelTopology(grid));
        ++stats.whole_grid_counts;
      }
      if (after.shells == topology->shells && after.cavities == topology->cavities &&
          after.genus == topology->genus + 1) {
        ++stats.opened;
        stats.carved_voxels += static_cast<int64_t>(plug.path.size());
        topology = after;
      } else {
        ++stats.refused;
        for (auto it = undo.rbegin(); it != undo.rend(); ++it) s[it->first] = it->second;
      }
      if (!IsBoundary(s[i]) || IsHard(s[i])) break;
    }
    return true;
  };
  // Until the first carve the grid is as it was, and a voxel none of whose staircases passes
  // Walk and Surrounded does nothing: those voxels are found first, a z plane a task on
  // `threads`, and visited in index order. From the first carve on (opened or refused: the
  // grid it reads may differ) every boundary voxel after it is visited, one at a time.
  std::vector<std::vector<int64_t>> candidates(static_cast<size_t>(std::max(grid.dim(2), 2)));
  const auto scan_row = [&](int64_t row, int x, auto on_voxel) {
    for (; x + 1 < grid.dim(0); ++x) {
      const int64_t i = row + x;
      // Eight voxels at a time where none is a boundary voxel (nearly everywhere; a carve
      // changes only voxels around the one being tested, which are read after it).
      if (x + 8 <= grid.dim(0) - 1 && !AnyBoundary8(s + i)) {
        x += 7;
        continue;
      }
      if (!IsBoundary(s[i]) || IsHard(s[i])) continue;
      if (!on_voxel(i)) return false;
    }
    return true;
  };
  RunTasks(std::max(threads, 1), grid.dim(2) - 2, [&](int, int64_t task) {
    const int z = static_cast<int>(task) + 1;
    Plug trial;
    if (cancel.cancelled()) return;
    for (int y = 1; y + 1 < grid.dim(1); ++y) {
      scan_row(grid.Index(0, y, z), 1, [&](int64_t i) {
        for (const Coord& dir : kDirections) {
          if (finder.Walk(i, dir, trial) && finder.Surrounded(trial)) {
            candidates[static_cast<size_t>(z)].push_back(i);
            break;
          }
        }
        return true;
      });
    }
  });
  if (cancel.cancelled()) return absl::CancelledError("reconstruction cancelled");
  int64_t carved_after = -1;  // the voxel after the first carve
  for (const std::vector<int64_t>& plane : candidates) {
    for (int64_t i : plane) {
      if (!visit(i)) return done();
      if (stats.opened + stats.refused > 0) {
        carved_after = i + 1;
        break;
      }
    }
    if (carved_after >= 0) break;
  }
  if (carved_after < 0) return done();
  const Coord from = grid.CoordOf(carved_after);
  for (int z = std::max(from.z, 1); z + 1 < grid.dim(2); ++z) {
    if (cancel.cancelled()) return absl::CancelledError("reconstruction cancelled");
    for (int y = z == from.z ? std::max(from.y, 1) : 1; y + 1 < grid.dim(1); ++y) {
      const int x = z == from.z && y == from.y ? std::max(from.x, 1) : 1;
      if (!scan_row(grid.Index(0, y, z), x, visit)) return done();
    }
  }
  return done();
}

}  // namespace membrane

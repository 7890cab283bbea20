#include "core/mesh/corner_crease.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/base/parallel_tasks.h"
#include "core/mesh/angle_sectors.h"

namespace membrane {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A sector's band members around a position: the nearest `keep` (nearest first, the lower
// index first among equal distances, so that the order the members are read in does not
// matter) and the sum of every member's position with its count.
struct Sector {
  std::vector<double> d2;
  std::vector<int> member;
  Vec3d all{0, 0, 0};
  int64_t count = 0;

  void Clear() {
    d2.clear();
    member.clear();
    all = Vec3d{0, 0, 0};
    count = 0;
  }
  // Whether (d, i) comes before the kept member at `at`.
  bool Before(double d, int i, size_t at) const {
    return d < d2[at] || (d == d2[at] && i < member[at]);
  }
  // `sum` the position times `weight` (the members it stands for).
  void Add(const Vec3d& sum, int weight, double d, int i, int keep) {
    all = all + sum;
    count += weight;
    if (static_cast<int>(d2.size()) == keep && !Before(d, i, d2.size() - 1)) return;
    size_t at = d2.size();
    if (static_cast<int>(d2.size()) < keep) {
      d2.push_back(d);
      member.push_back(i);
    } else {
      --at;
    }
    for (; at > 0 && Before(d, i, at - 1); --at) {
      d2[at] = d2[at - 1];
      member[at] = member[at - 1];
    }
    d2[at] = d;
    member[at] = i;
  }
};

// The band by cell of a cubic grid over its box: the members of the cells near a position
// one by one, and each farther cell as one member at the mean of its members' positions and
// normals, weighing their count. Exact where the sides are read; beyond, the cost is a cell's.
class BandCells {
 public:
  // At most about kMaxCellsPerAxis cells along the box's longest side.
  static constexpr double kMaxCellsPerAxis = 64;
  // Cells a reach: the far band is read at a quarter of the reach.
  static constexpr double kCellsPerReach = 4;

  // Members 0..n-1 are the band's (positions, normals); n + c is cell c's mean.
  BandCells(absl::Span<const Vec3d> positions, absl::Span<const Vec3d> normals, double reach)
      : n_(static_cast<int>(positions.size())) {
    if (positions.empty()) return;
    Vec3d lo = positions[0], hi = positions[0];
    for (const Vec3d& p : positions)
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
    lo_ = lo;
    const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    cell_ = std::max({reach / kCellsPerReach, extent / kMaxCellsPerAxis, 1e-9});
    span_ = static_cast<int64_t>(std::ceil(reach / cell_));
    for (int k = 0; k < 3; ++k) dims_[k] = CellOf(hi[k], k) + 1;
    // Each member's cell, then the occupied cells in increasing order, their members in
    // increasing order.
    std::vector<int64_t> of(positions.size());
    for (size_t i = 0; i < positions.size(); ++i)
      of[i] = CellOf(positions[i][0], 0) +
              dims_[0] * (CellOf(positions[i][1], 1) + dims_[1] * CellOf(positions[i][2], 2));
    members_.resize(positions.size());
    for (size_t i = 0; i < members_.size(); ++i) members_[i] = static_cast<int>(i);
    std::stable_sort(members_.begin(), members_.end(),
                     [&](int a, int b) { return of[a] < of[b]; });
    for (size_t j = 0; j < members_.size(); ++j) {
      if (j == 0 || of[members_[j]] != of[members_[j - 1]]) {
        const int64_t c = of[members_[j]];
        cells_.push_back({{c % dims_[0], (c / dims_[0]) % dims_[1], c / (dims_[0] * dims_[1])},
                          static_cast<int>(j), static_cast<int>(j)});
      }
      ++cells_.back().end;
    }
    points_.assign(positions.begin(), positions.end());
    normals_.assign(normals.begin(), normals.end());
    weights_.assign(positions.size(), 1);
    for (const Cell& c : cells_) {
      Vec3d p{0, 0, 0}, m{0, 0, 0};
      for (int j = c.begin; j < c.end; ++j) {
        p = p + positions[members_[j]];
        m = m + normals[members_[j]];
      }
      const double w = 1.0 / (c.end - c.begin);
      points_.push_back(w * p);
      normals_.push_back(w * m);
      weights_.push_back(c.end - c.begin);
    }
  }

  // Calls fn(i) for every band member i in the cells within a reach of p's cell (along each
  // axis), and for each farther occupied cell, with i its mean's index.
  template <typename Fn>
  void ForEach(const Vec3d& p, Fn fn) const {
    const std::array<int64_t, 3> at{CellOf(p[0], 0), CellOf(p[1], 1), CellOf(p[2], 2)};
    for (size_t c = 0; c < cells_.size(); ++c) {
      const Cell& cell = cells_[c];
      if (std::abs(cell.xyz[0] - at[0]) <= span_ && std::abs(cell.xyz[1] - at[1]) <= span_ &&
          std::abs(cell.xyz[2] - at[2]) <= span_) {
        for (int j = cell.begin; j < cell.end; ++j) fn(members_[j]);
      } else {
        fn(n_ + static_cast<int>(c));
      }
    }
  }

  const Vec3d& point(int i) const { return points_[i]; }
  const Vec3d& normal(int i) const { return normals_[i]; }
  int weight(int i) const { return weights_[i]; }

 private:
  struct Cell {
    std::array<int64_t, 3> xyz;
    int begin, end;  // its members in members_
  };

  // Clamped to 4 box lengths either side (the occupied cells lie in [0, kMaxCellsPerAxis]): a
  // position clamped is farther than a reach from every occupied cell, as it is unclamped.
  int64_t CellOf(double x, int k) const {
    const double c = std::floor((x - lo_[k]) / cell_);
    return static_cast<int64_t>(std::clamp(c, -4 * kMaxCellsPerAxis, 4 * kMaxCellsPerAxis));
  }

  int n_ = 0;
  Vec3d lo_{0, 0, 0};
  double cell_ = 1;
  int64_t span_ = 1;
  std::array<int64_t, 3> dims_{0, 0, 0};
  std::vector<Cell> cells_;
  std::vector<int> members_;
  std::vector<Vec3d> points_, normals_;
  std::vector<int> weights_;
};

// One worker's sectors and their sides.
struct SectorScratch {
  explicit SectorScratch(int sectors)
      : near(static_cast<size_t>(sectors)), centre(sectors), normal(sectors), flat(sectors) {}
  std::vector<Sector> near;
  std::vector<Vec3d> centre, normal;
  std::vector<char> flat;
};

}  // namespace

int CreaseToCorner(absl::Span<const Vec3d> positions, absl::Span<const Vec3d> normals,
                   const Vec3d& axis, const CornerCreaseOptions& options,
                   absl::Span<Vec3d> cap, int threads) {
  const int sectors = std::clamp(options.sectors - options.sectors % 2, 2, 360);
  const int keep = std::max(1, options.per_sector);
  const double max_cosine = std::cos(options.min_angle * kPi / 180.0);
  const Vec3d t1 = Normalized(std::abs(axis[0]) < 0.9 ? Cross(axis, Vec3d{1, 0, 0})
                                                      : Cross(axis, Vec3d{0, 1, 0}));
  const Vec3d t2 = Cross(axis, t1);
  const BandCells band(positions, normals, options.reach);
  const AngleSectors sector_of(sectors);
  const int workers = std::max(threads, 1);
  std::vector<SectorScratch> scratch(static_cast<size_t>(workers), SectorScratch(sectors));
  // A cap of fewer than 512 positions stays on the calling thread, where the threads' start
  // would cost more than its reading of the band.
  const TaskRanges ranges = TaskRanges::Split(static_cast<int64_t>(cap.size()), threads, 8, 512);
  std::vector<int> moved(static_cast<size_t>(ranges.tasks), 0);
  RunTasks(threads, ranges.tasks, [&](int worker, int64_t task) {
    SectorScratch& s = scratch[worker];
    for (int64_t j = ranges.begin(task); j < ranges.end(task); ++j) {
      Vec3d& p = cap[j];
      for (Sector& sector : s.near) sector.Clear();
      band.ForEach(p, [&](int i) {
        const Vec3d d = band.point(i) - p;
        const int k = sector_of(Dot(d, t2), Dot(d, t1));
        const int w = band.weight(i);
        s.near[k].Add(w * band.point(i), w, SquaredNorm(d), i, keep);
      });
      for (int k = 0; k < sectors; ++k) {
        const Sector& sector = s.near[k];
        Vec3d sum{0, 0, 0}, n{0, 0, 0};
        for (int i : sector.member) {
          sum = sum + band.point(i);
          n = n + band.normal(i);
        }
        if (!sector.member.empty()) sum = (1.0 / static_cast<double>(sector.member.size())) * sum;
        s.centre[k] = sum;
        s.normal[k] = Normalized(n);
        const Vec3d mean = (1.0 / static_cast<double>(std::max<int64_t>(sector.count, 1))) *
                           sector.all;
        s.flat[k] = sector.count > 0 && Dot(mean - sum, s.normal[k]) <= options.flat_tolerance;
      }
      double best = 0;
      Vec3d along{0, 0, 0};
      for (int a = 0; a < sectors / 2; ++a) {
        const int b = a + sectors / 2;
        if (s.near[a].member.empty() || s.near[b].member.empty() || !s.flat[a] || !s.flat[b])
          continue;
        const Vec3d& na = s.normal[a];
        const Vec3d& nb = s.normal[b];
        if (!(Dot(na, nb) <= max_cosine)) continue;
        const double ha = Dot(p - s.centre[a], na), hb = Dot(p - s.centre[b], nb);
        if (!(ha > 0 && hb > 0)) continue;
        // A concave corner: each side lies outside the other's plane (at a convex edge, or
        // round a post, each lies inside).
        if (!(Dot(s.centre[a] - s.centre[b], nb) > 0 && Dot(s.centre[b] - s.centre[a], na) > 0))
          continue;
        // Inward along the normals' mean until the first plane: the union's boundary, by a
        // move that varies continuously with p (the nearer plane's foot jumps across the
        // bisector).
        const Vec3d m = Normalized(na + nb);
        const double ca = Dot(na, m), cb = Dot(nb, m);
        if (!(ca > 0.1 && cb > 0.1)) continue;
        const double t = std::min({ha / ca, hb / cb, options.max_move});
        if (t > best) {
          best = t;
          along = m;
        }
      }
      if (!(best > 0)) continue;
      p = p - best * along;
      ++moved[task];
    }
  });
  int total = 0;
  for (int m : moved) total += m;
  return total;
}

}  // namespace membrane

#include "core/mesh/surface_deviation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <utility>

#include "absl/container/flat_hash_map.h"
#include "core/base/parallel_tasks.h"
#include "core/geometry/vec3.h"

namespace membrane {
namespace {

constexpr int64_t kPointsPerTask = 16384;

// Squared distance from p to triangle (a, b, c): the closest point by Voronoi regions
// (Ericson, Real-Time Collision Detection, 5.1.5).
double SquaredDistanceToTriangle(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const Vec3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = Dot(ab, ap), d2 = Dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return SquaredNorm(ap);
  const Vec3d bp = p - b;
  const double d3 = Dot(ab, bp), d4 = Dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return SquaredNorm(bp);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return SquaredNorm(p - (a + v * ab));
  }
  const Vec3d cp = p - c;
  const double d5 = Dot(ab, cp), d6 = Dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return SquaredNorm(cp);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return SquaredNorm(p - (a + w * ac));
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return SquaredNorm(p - (b + w * (c - b)));
  }
  const double denom = va + vb + vc;
  if (!(std::fabs(denom) > 0)) {
    // Degenerate: the nearest of its three edges' ends already tested above covers points;
    // fall back to the vertices.
    return std::min({SquaredNorm(ap), SquaredNorm(bp), SquaredNorm(cp)});
  }
  const double v = vb / denom, w = vc / denom;
  return SquaredNorm(p - (a + v * ab + w * ac));
}

// Faces by cell, as ranges of one array.
class CellFaces {
 public:
  CellFaces(const TriangleMesh& mesh, const std::vector<int32_t>& faces, double cell)
      : inverse_cell_(1 / cell) {
    std::vector<std::pair<uint64_t, int32_t>> entries;
    for (int32_t f : faces) {
      std::array<int64_t, 3> lo, hi;
      Range(mesh, f, lo, hi);
      for (int64_t z = lo[2]; z <= hi[2]; ++z)
        for (int64_t y = lo[1]; y <= hi[1]; ++y)
          for (int64_t x = lo[0]; x <= hi[0]; ++x) entries.push_back({Key(x, y, z), f});
      for (int k = 0; k < 3; ++k) {
        low_[k] = std::min(low_[k], lo[k]);
        high_[k] = std::max(high_[k], hi[k]);
      }
    }
    std::sort(entries.begin(), entries.end());
    faces_.resize(entries.size());
    for (size_t i = 0; i < entries.size(); ++i) {
      faces_[i] = entries[i].second;
      auto [it, inserted] = ranges_.try_emplace(entries[i].first, i, i + 1);
      if (!inserted) it->second.second = i + 1;
    }
  }

  double cell() const { return 1 / inverse_cell_; }
  std::array<int64_t, 3> CellOf(const Vec3d& p) const {
    return {static_cast<int64_t>(std::floor(p[0] * inverse_cell_)),
            static_cast<int64_t>(std::floor(p[1] * inverse_cell_)),
            static_cast<int64_t>(std::floor(p[2] * inverse_cell_))};
  }
  // Cells of Chebyshev ring r around c that can hold faces (the grid's box).
  template <typename Visit>
  void ForEachInRing(const std::array<int64_t, 3>& c, int64_t r, Visit&& visit) const {
    auto cell = [&](int64_t x, int64_t y, int64_t z) {
      if (x < low_[0] || x > high_[0]) return;
      const auto it = ranges_.find(Key(x, y, z));
      if (it == ranges_.end()) return;
      for (size_t i = it->second.first; i < it->second.second; ++i) visit(faces_[i]);
    };
    for (int64_t z = std::max(c[2] - r, low_[2]); z <= std::min(c[2] + r, high_[2]); ++z)
      for (int64_t y = std::max(c[1] - r, low_[1]); y <= std::min(c[1] + r, high_[1]); ++y) {
        if (std::abs(z - c[2]) == r || std::abs(y - c[1]) == r) {
          for (int64_t x = c[0] - r; x <= c[0] + r; ++x) cell(x, y, z);
        } else {
          cell(c[0] - r, y, z);
          if (r > 0) cell(c[0] + r, y, z);
        }
      }
  }
  // The largest ring around c that still meets the grid's box.
  int64_t LastRing(const std::array<int64_t, 3>& c) const {
    int64_t r = 0;
    for (int k = 0; k < 3; ++k) r = std::max({r, std::abs(c[k] - low_[k]), std::abs(high_[k] - c[k])});
    return r;
  }

 private:
  void Range(const TriangleMesh& mesh, int32_t f, std::array<int64_t, 3>& lo,
             std::array<int64_t, 3>& hi) const {
    for (int k = 0; k < 3; ++k) {
      float a = mesh.vertices[mesh.faces[f][0]][k], b = a;
      for (int j = 1; j < 3; ++j) {
        a = std::min(a, mesh.vertices[mesh.faces[f][j]][k]);
        b = std::max(b, mesh.vertices[mesh.faces[f][j]][k]);
      }
      lo[k] = static_cast<int64_t>(std::floor(a * inverse_cell_));
      hi[k] = static_cast<int64_t>(std::floor(b * inverse_cell_));
    }
  }
  static uint64_t Key(int64_t x, int64_t y, int64_t z) {
    constexpr uint64_t kMask = (uint64_t{1} << 21) - 1;
    return (static_cast<uint64_t>(x) & kMask) | (static_cast<uint64_t>(y) & kMask) << 21 |
           (static_cast<uint64_t>(z) & kMask) << 42;
  }

  double inverse_cell_;
  std::array<int64_t, 3> low_{std::numeric_limits<int64_t>::max(),
                              std::numeric_limits<int64_t>::max(),
                              std::numeric_limits<int64_t>::max()};
  std::array<int64_t, 3> high_{std::numeric_limits<int64_t>::min(),
                               std::numeric_limits<int64_t>::min(),
                               std::numeric_limits<int64_t>::min()};
  std::vector<int32_t> faces_;
  absl::flat_hash_map<uint64_t, std::pair<size_t, size_t>> ranges_;
};

}  // namespace

SurfaceDeviation MeasureDeviation(const std::vector<Point3f>& points, const TriangleMesh& mesh,
                                  int threads, const CancelToken& cancel) {
  SurfaceDeviation result;
  const int64_t nv = static_cast<int64_t>(mesh.vertices.size());
  std::vector<int32_t> faces;
  double edge_sum = 0;
  for (int32_t f = 0; f < static_cast<int32_t>(mesh.faces.size()); ++f) {
    const auto& c = mesh.faces[f];
    if (c[0] < 0 || c[0] >= nv || c[1] < 0 || c[1] >= nv || c[2] < 0 || c[2] >= nv) continue;
    faces.push_back(f);
    edge_sum += Norm(ToVec3d(mesh.vertices[c[1]]) - ToVec3d(mesh.vertices[c[0]]));
  }
  if (faces.empty() || points.empty()) return result;
  // Cells about as large as the faces: most points find their nearest face in their own cell
  // or the ring around it.
  const double cell = edge_sum > 0 ? edge_sum / faces.size() : 1.0;
  const CellFaces grid(mesh, faces, cell);

  const int64_t n = static_cast<int64_t>(points.size());
  const int64_t tasks = (n + kPointsPerTask - 1) / kPointsPerTask;
  std::vector<double> task_max(tasks, 0), task_sum(tasks, 0);
  std::vector<int64_t> task_count(tasks, 0);
  TaskCancel stop(cancel, threads, 1);
  // Per worker, the point each face was last measured for: a face entered in several cells is
  // measured once per point.
  const int workers = std::max(threads, 1);
  std::vector<std::vector<int64_t>> seen(workers);
  RunTasks(threads, tasks, [&](int worker, int64_t t) {
    if (stop.Poll(worker)) return;
    std::vector<int64_t>& last_point = seen[worker];
    if (last_point.empty()) last_point.assign(mesh.faces.size(), -1);
    for (int64_t i = t * kPointsPerTask; i < std::min(n, (t + 1) * kPointsPerTask); ++i) {
      const Vec3d p = ToVec3d(points[i]);
      const std::array<int64_t, 3> c = grid.CellOf(p);
      // How far p is from the walls of its own cell: after ring r, every face not yet seen
      // lies outside the cube of rings 0..r, at least r cells plus this much away.
      double wall = grid.cell();
      for (int k = 0; k < 3; ++k) {
        const double low = p[k] - static_cast<double>(c[k]) * grid.cell();
        wall = std::min({wall, low, grid.cell() - low});
      }
      wall = std::max(wall, 0.0);
      double best = std::numeric_limits<double>::infinity();
      const int64_t last = grid.LastRing(c);
      for (int64_t r = 0; r <= last; ++r) {
        grid.ForEachInRing(c, r, [&](int32_t f) {
          if (last_point[f] == i) return;
          last_point[f] = i;
          const auto& v = mesh.faces[f];
          best = std::min(best, SquaredDistanceToTriangle(p, ToVec3d(mesh.vertices[v[0]]),
                                                          ToVec3d(mesh.vertices[v[1]]),
                                                          ToVec3d(mesh.vertices[v[2]])));
        });
        const double reach = static_cast<double>(r) * grid.cell() + wall;
        if (best <= reach * reach) break;
      }
      const double d = std::sqrt(best);
      task_max[t] = std::max(task_max[t], d);
      task_sum[t] += d;
      ++task_count[t];
    }
  });
  double sum = 0;
  for (int64_t t = 0; t < tasks; ++t) {
    result.max = std::max(result.max, task_max[t]);
    sum += task_sum[t];
    result.points += task_count[t];
  }
  result.mean = result.points > 0 ? sum / result.points : 0;
  return result;
}

}  // namespace membrane

#include "core/engine/point_noise.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "core/geometry/cholesky_solve.h"
#include "core/geometry/symmetric_eigen3.h"

namespace membrane {
namespace {

constexpr int kMinBoxPoints = 12;
constexpr int kMaxBoxPoints = 256;
constexpr int kQuadricTerms = 6;
// A pivot of the quadric's normal equations below this fraction of their largest diagonal
// entry: the points do not pin a quadric down (a strip, a line).
constexpr double kMinPivot = 1e-9;
constexpr int64_t kCancelStride = 65536;

using Cell = std::array<int64_t, 3>;
using Vec = std::array<double, 3>;

Cell CellOf(const Vec& p, const Box3d& bounds, double cell) {
  Cell c;
  for (int d = 0; d < 3; ++d) c[d] = static_cast<int64_t>(std::floor((p[d] - bounds.min[d]) / cell));
  return c;
}

// The residual of the height quadric over the best plane of `q` (coordinates relative to the
// box's centre, in half-widths), in half-widths; nullopt when the fit is not determined.
std::optional<double> QuadricResidual(const std::vector<Vec>& q) {
  const double n = static_cast<double>(q.size());
  Vec mean{0, 0, 0};
  for (const Vec& p : q) {
    for (int d = 0; d < 3; ++d) mean[d] += p[d];
  }
  for (double& m : mean) m /= n;
  SymmetricMatrix3 cov{};
  for (const Vec& p : q) {
    const Vec r = {p[0] - mean[0], p[1] - mean[1], p[2] - mean[2]};
    cov[0] += r[0] * r[0];
    cov[1] += r[0] * r[1];
    cov[2] += r[0] * r[2];
    cov[3] += r[1] * r[1];
    cov[4] += r[1] * r[2];
    cov[5] += r[2] * r[2];
  }
  const std::optional<Vec> found = EigenvectorOf(cov, SymmetricEigenvalues(cov).smallest);
  if (!found) return std::nullopt;
  const Vec& normal = *found;
  // A tangent: the normal crossed with the axis it leans on least.
  int least = 0;
  for (int d = 1; d < 3; ++d) {
    if (std::abs(normal[d]) < std::abs(normal[least])) least = d;
  }
  Vec axis{0, 0, 0};
  axis[least] = 1;
  Vec t1 = Cross(normal, axis);
  const double len = std::sqrt(Dot(t1, t1));
  for (double& x : t1) x /= len;
  const Vec t2 = Cross(normal, t1);

  SquareMatrix<kQuadricTerms> ata{};
  std::array<double, kQuadricTerms> atw{};
  std::vector<std::array<double, kQuadricTerms + 1>> rows;
  rows.reserve(q.size());
  for (const Vec& p : q) {
    const Vec r = {p[0] - mean[0], p[1] - mean[1], p[2] - mean[2]};
    const double u = Dot(r, t1), v = Dot(r, t2), w = Dot(r, normal);
    const std::array<double, kQuadricTerms> t = {1, u, v, u * u, u * v, v * v};
    for (int i = 0; i < kQuadricTerms; ++i) {
      for (int j = 0; j < kQuadricTerms; ++j) ata[i][j] += t[i] * t[j];
      atw[i] += t[i] * w;
    }
    rows.push_back({1, u, v, u * u, u * v, v * v, w});
  }
  double largest = 0;
  for (int i = 0; i < kQuadricTerms; ++i) largest = std::max(largest, ata[i][i]);
  if (!CholeskySolve(ata, atw, 0, kMinPivot * largest)) return std::nullopt;
  double ssr = 0;
  for (const auto& row : rows) {
    double fit = 0;
    for (int i = 0; i < kQuadricTerms; ++i) fit += atw[i] * row[i];
    const double e = row[kQuadricTerms] - fit;
    ssr += e * e;
  }
  return std::sqrt(ssr / (n - kQuadricTerms));
}

}  // namespace

PointNoise MeasurePointNoise(absl::Span<const Point3f> points, const Box3d& bounds,
                             double half_width, const CancelToken& cancel, int boxes) {
  const int64_t n = static_cast<int64_t>(points.size());
  if (n == 0 || boxes <= 0 || !(half_width > 0)) return {};
  const int count = static_cast<int>(std::min<int64_t>(boxes, n));
  // Each box is a cube of side 2 half_width: over cells of that side it meets at most 8.
  const double cell = 2 * half_width;
  std::vector<Vec> centres(count);
  std::vector<std::vector<Vec>> inside(count);
  absl::flat_hash_map<Cell, std::vector<int>> seeds_of_cell;
  for (int k = 0; k < count; ++k) {
    const Point3f& p = points[static_cast<int64_t>((k + 0.5) * static_cast<double>(n) / count)];
    centres[k] = {p[0], p[1], p[2]};
    const Cell lo = CellOf({p[0] - half_width, p[1] - half_width, p[2] - half_width}, bounds, cell);
    const Cell hi = CellOf({p[0] + half_width, p[1] + half_width, p[2] + half_width}, bounds, cell);
    for (int64_t z = lo[2]; z <= hi[2]; ++z) {
      for (int64_t y = lo[1]; y <= hi[1]; ++y) {
        for (int64_t x = lo[0]; x <= hi[0]; ++x) seeds_of_cell[{x, y, z}].push_back(k);
      }
    }
  }
  for (int64_t i = 0; i < n; ++i) {
    if (i % kCancelStride == 0 && cancel.cancelled()) return {};
    const Vec p = {points[i][0], points[i][1], points[i][2]};
    const auto it = seeds_of_cell.find(CellOf(p, bounds, cell));
    if (it == seeds_of_cell.end()) continue;
    std::vector<int>& seeds = it->second;
    for (size_t s = 0; s < seeds.size();) {
      const int k = seeds[s];
      // A full box leaves the cell's list, so that points crowded into one spot cost one
      // lookup each once its boxes are full.
      if (inside[k].size() >= kMaxBoxPoints) {
        seeds[s] = seeds.back();
        seeds.pop_back();
        continue;
      }
      const Vec& c = centres[k];
      const Vec r = {(p[0] - c[0]) / half_width, (p[1] - c[1]) / half_width,
                     (p[2] - c[2]) / half_width};
      if (std::max({std::abs(r[0]), std::abs(r[1]), std::abs(r[2])}) <= 1) inside[k].push_back(r);
      ++s;
    }
  }
  std::vector<double> residuals;
  residuals.reserve(count);
  for (const std::vector<Vec>& q : inside) {
    if (static_cast<int>(q.size()) < kMinBoxPoints) continue;
    if (const std::optional<double> r = QuadricResidual(q)) residuals.push_back(*r * half_width);
  }
  PointNoise noise;
  noise.fitted_boxes = static_cast<int>(residuals.size());
  if (noise.fitted_boxes < kNoiseMinFittedBoxes) return noise;
  const auto mid = residuals.begin() + residuals.size() / 2;
  std::nth_element(residuals.begin(), mid, residuals.end());
  noise.sigma = *mid;
  return noise;
}

double NoiseAwareVoxelSize(double formula_size, const PointNoise& noise) {
  return std::max(formula_size, noise.sigma / kVoxelNoiseShare);
}

bool VoxelRaisedForNoise(double formula_size, double voxel_size) {
  return formula_size > 0 && voxel_size > formula_size;
}

}  // namespace membrane

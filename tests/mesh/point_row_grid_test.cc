#include "core/mesh/point_row_grid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "gtest/gtest.h"

namespace membrane {
namespace {

// The points a brute-force scan finds within the radius, against the grid's.
std::vector<int> WithinBrute(const std::vector<Point3f>& points, const Vec3d& c, double r) {
  std::vector<int> out;
  for (size_t i = 0; i < points.size(); ++i) {
    const double dx = points[i][0] - c[0], dy = points[i][1] - c[1], dz = points[i][2] - c[2];
    if (dx * dx + dy * dy + dz * dz <= r * r) out.push_back(static_cast<int>(i));
  }
  return out;
}

TEST(PointRowGrid, FindsExactlyThePointsWithinTheRadius) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> coord(-5, 5);
  std::vector<Point3f> points(3000);
  for (Point3f& p : points) p = {coord(rng), coord(rng), 0.2f * coord(rng)};
  const PointRowGrid grid(points, 0.5);
  std::uniform_real_distribution<double> centre(-7, 7);
  for (int q = 0; q < 300; ++q) {
    const Vec3d c{centre(rng), centre(rng), 0.3 * centre(rng)};
    const double r = 0.1 + (q % 7) * 0.4;
    size_t found = 0;
    grid.ForEachWithin(c, r, [&](const Point3f& p, double d2) {
      EXPECT_LE(d2, r * r);
      const double dx = p[0] - c[0], dy = p[1] - c[1], dz = p[2] - c[2];
      EXPECT_EQ(d2, dx * dx + dy * dy + dz * dz);
      ++found;
    });
    EXPECT_EQ(found, WithinBrute(points, c, r).size()) << "query " << q;
  }
}

TEST(PointRowGrid, PointsOnCellWallsAndOnTheSphereAreFound) {
  // A lattice on the cell walls, queried from lattice points and wall midpoints with radii that
  // put many points exactly on the sphere: the skipped rows and cells must never hold one.
  std::vector<Point3f> points;
  for (int z = -4; z <= 4; ++z)
    for (int y = -4; y <= 4; ++y)
      for (int x = -4; x <= 4; ++x)
        points.push_back({0.25f * x, 0.25f * y, 0.25f * z});
  const PointRowGrid grid(points, 0.25);
  for (const Vec3d& c : {Vec3d{0, 0, 0}, Vec3d{0.125, 0, 0.25}, Vec3d{0.5, -0.25, 0.125}})
    for (double r : {0.25, 0.5, std::sqrt(2 * 0.0625), std::sqrt(3 * 0.0625), 0.75, 1.0}) {
      size_t found = 0;
      grid.ForEachWithin(c, r, [&](const Point3f&, double) { ++found; });
      EXPECT_EQ(found, WithinBrute(points, c, r).size()) << c[0] << " " << c[1] << " " << r;
    }
}

TEST(PointRowGrid, SparseCloudInAHugeBoxStaysSmallAndCorrect) {
  // Two clusters far apart: the cells coarsen instead of covering the gap finely.
  const std::vector<Point3f> points = {
      {0, 0, 0}, {0.1f, 0, 0}, {1e6f, 1e6f, 1e6f}, {1e6f, 1e6f, 1e6f + 0.1f}};
  const PointRowGrid grid(points, 0.01);
  EXPECT_LE(grid.bytes(), size_t{9} << 20);  // 2^21 offsets and the points
  int found = 0;
  grid.ForEachWithin({1e6, 1e6, 1e6}, 0.5, [&](const Point3f&, double) { ++found; });
  EXPECT_EQ(found, 2);
  found = 0;
  grid.ForEachWithin({-5e6, 0, 0}, 1, [&](const Point3f&, double) { ++found; });
  EXPECT_EQ(found, 0);
}

TEST(PointRowGrid, EmptyCloudFindsNothing) {
  const PointRowGrid grid({}, 1.0);
  int found = 0;
  grid.ForEachWithin({0, 0, 0}, 10, [&](const Point3f&, double) { ++found; });
  EXPECT_EQ(found, 0);
}

// The dense index the grid must agree with: one offset per cell of the whole box, the cells as
// asked, the points counting-sorted into (z, y, x) cell order (stable), one run per (y, z) row
// of a query's box that holds a point.
class DenseIndex {
 public:
  DenseIndex(const std::vector<Point3f>& points, double cell) : cell_(cell) {
    std::array<double, 3> hi;
    for (int k = 0; k < 3; ++k) lo_[k] = hi[k] = points[0][k];
    for (const Point3f& p : points)
      for (int k = 0; k < 3; ++k) {
        lo_[k] = std::min<double>(lo_[k], p[k]);
        hi[k] = std::max<double>(hi[k], p[k]);
      }
    const double max_cells = std::max(16.0 * points.size(), double(1 << 21));
    for (;;) {
      double cells = 1;
      for (int k = 0; k < 3; ++k) {
        dims_[k] = static_cast<int64_t>(std::floor((hi[k] - lo_[k]) / cell_)) + 1;
        cells *= dims_[k];
      }
      if (cells <= max_cells) break;
      cell_ *= 1.25;
    }
    start_.assign(dims_[0] * dims_[1] * dims_[2] + 1, 0);
    std::vector<int64_t> cell_of(points.size());
    for (size_t i = 0; i < points.size(); ++i) {
      int64_t c[3];
      for (int k = 0; k < 3; ++k)
        c[k] = std::clamp<int64_t>(CellOf(points[i][k], k), 0, dims_[k] - 1);
      cell_of[i] = c[0] + dims_[0] * (c[1] + dims_[1] * c[2]);
      ++start_[cell_of[i] + 1];
    }
    for (size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    stored.resize(points.size());
    std::vector<uint32_t> fill(start_.begin(), start_.end() - 1);
    for (size_t i = 0; i < points.size(); ++i) stored[fill[cell_of[i]]++] = points[i];
  }

  std::vector<std::pair<uint32_t, uint32_t>> Runs(const Vec3d& centre, double radius) const {
    std::vector<std::pair<uint32_t, uint32_t>> runs;
    std::array<int64_t, 3> lo, hi;
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::max<int64_t>(CellOf(centre[k] - radius, k), 0);
      hi[k] = std::min<int64_t>(CellOf(centre[k] + radius, k), dims_[k] - 1);
      if (lo[k] > hi[k]) return runs;
    }
    for (int64_t z = lo[2]; z <= hi[2]; ++z)
      for (int64_t y = lo[1]; y <= hi[1]; ++y) {
        const int64_t row = dims_[0] * (y + dims_[1] * z);
        const uint32_t begin = start_[row + lo[0]], end = start_[row + hi[0] + 1];
        if (begin < end) runs.emplace_back(begin, end);
      }
    return runs;
  }

  double cell() const { return cell_; }
  std::vector<Point3f> stored;

 private:
  int64_t CellOf(double v, int axis) const {
    double c = (v - lo_[axis]) / cell_;
    if (!(c >= -1.0)) c = -1.0;
    if (c > double(dims_[axis])) c = double(dims_[axis]);
    return static_cast<int64_t>(std::floor(c));
  }

  double cell_;
  std::array<double, 3> lo_;
  std::array<int64_t, 3> dims_;
  std::vector<uint32_t> start_;
};

// The grid built on 1 and 3 threads against the dense index: the same stored points and, for
// queries around and between the points (centres on cell walls among them), the same runs.
void ExpectSameAsDense(const std::vector<Point3f>& points, double cell,
                       const PointRowGrid::Limits& limits, PointRowGrid::Layout layout,
                       std::mt19937& rng) {
  const DenseIndex dense(points, cell);
  for (int threads : {1, 3}) {
    const PointRowGrid grid(points, cell, threads, limits);
    ASSERT_EQ(grid.layout(), layout);
    ASSERT_EQ(grid.cell(), dense.cell());
    ASSERT_EQ(grid.num_points(), points.size());
    for (size_t i = 0; i < points.size(); ++i) {
      ASSERT_EQ(grid.xs()[i], dense.stored[i][0]) << i;
      ASSERT_EQ(grid.ys()[i], dense.stored[i][1]) << i;
      ASSERT_EQ(grid.zs()[i], dense.stored[i][2]) << i;
    }
    // The paddings copy the last stored point.
    for (size_t i = points.size(); i < points.size() + PointRowGrid::kTail; ++i) {
      ASSERT_EQ(grid.xs()[i], dense.stored.back()[0]);
      ASSERT_EQ(grid.ys()[i], dense.stored.back()[1]);
      ASSERT_EQ(grid.zs()[i], dense.stored.back()[2]);
    }
    std::uniform_int_distribution<size_t> pick(0, points.size() - 1);
    std::uniform_real_distribution<double> jitter(-3, 3), radius(0.3, 4.5);
    for (int q = 0; q < 3000; ++q) {
      const Point3f& p = points[pick(rng)];
      Vec3d c{p[0] + jitter(rng) * cell, p[1] + jitter(rng) * cell, p[2] + jitter(rng) * cell};
      if (q % 3 == 0)  // on a cell wall along each axis (the walls' multiples of `cell`)
        for (int k = 0; k < 3; ++k) c[k] = std::round(c[k] / cell) * cell;
      const double r = (q % 5 == 0 ? std::round(radius(rng)) : radius(rng)) * cell;
      std::vector<std::pair<uint32_t, uint32_t>> runs;
      grid.ForEachRun(c, r, [&](uint32_t b, uint32_t e) { runs.emplace_back(b, e); });
      ASSERT_EQ(runs, dense.Runs(c, r)) << "threads " << threads << " query " << q;
    }
  }
}

TEST(PointRowGrid, ReturnsWhatTheDenseIndexReturnsOnClusters) {
  // Gaussian clusters with empty rows and cells between them, a line along x (a long row) and
  // a lattice on the cell walls; more points than a task of the build, so 3 threads split it.
  // In a small box the grid keeps an offset per cell, in a large one its occupied cells.
  std::mt19937 rng(11);
  std::normal_distribution<float> spread(0, 0.15f);
  std::uniform_real_distribution<float> along(-2, 2);
  std::vector<Point3f> points;
  const std::array<std::array<float, 3>, 4> centres = {
      {{0, 0, 0}, {1.5f, -1, 0.5f}, {-1.2f, 1.3f, -0.8f}, {0.3f, 1.8f, 1.6f}}};
  for (int i = 0; i < 150000; ++i) {
    const auto& m = centres[i % 4];
    points.push_back({m[0] + spread(rng), m[1] + spread(rng), m[2] + spread(rng)});
  }
  for (int i = 0; i < 3000; ++i) points.push_back({along(rng), 0.7f, -0.4f});
  for (int z = -3; z <= 3; ++z)
    for (int y = -3; y <= 3; ++y)
      for (int x = -3; x <= 3; ++x) points.push_back({0.05f * x, 0.05f * y, 0.05f * z});
  ExpectSameAsDense(points, 0.05, {}, PointRowGrid::Layout::kDense, rng);
  ExpectSameAsDense(points, 0.05, {.max_dense_cells = 0}, PointRowGrid::Layout::kRowTable, rng);
  ExpectSameAsDense(points, 0.05, {.max_dense_cells = 0, .max_table_rows = 0},
                    PointRowGrid::Layout::kSparseRows, rng);
  // A cluster far off: a box larger than 16 cells a point, whose cells grow.
  for (int i = 0; i < 2000; ++i)
    points.push_back({12 + spread(rng), 12 + spread(rng), 12 + spread(rng)});
  ExpectSameAsDense(points, 0.05, {.max_dense_cells = 0}, PointRowGrid::Layout::kRowTable, rng);
}

TEST(PointRowGrid, ReturnsWhatTheDenseIndexReturnsInASparseBox) {
  // Clusters at the corners of a wide square across y and z, thin along x, its rows listed
  // alone (and, for comparison, the default dense box); one cluster is a lattice on the cell
  // walls.
  std::mt19937 rng(12);
  std::normal_distribution<float> spread(0, 0.3f);
  std::vector<Point3f> points;
  for (int i = 0; i < 20000; ++i) {
    const float y = (i % 4) & 1 ? 120.0f : 0.0f, z = (i % 4) & 2 ? 120.0f : 0.0f;
    points.push_back({0.1f + 0.05f * spread(rng), y + spread(rng), z + spread(rng)});
  }
  for (int z = 0; z <= 4; ++z)
    for (int y = 0; y <= 4; ++y) points.push_back({0.1f, 60.0f + 0.1f * y, 60.0f + 0.1f * z});
  const PointRowGrid::Limits sparse = {.max_dense_cells = 0, .max_table_rows = 0};
  const PointRowGrid grid(points, 0.1, 1, sparse);
  EXPECT_LT(grid.bytes(), 40 * points.size());  // the box's rows alone would be 4 bytes each
  ExpectSameAsDense(points, 0.1, sparse, PointRowGrid::Layout::kSparseRows, rng);
  ExpectSameAsDense(points, 0.1, {}, PointRowGrid::Layout::kDense, rng);
}

TEST(PointRowGrid, OnePointAndOneCell) {
  std::mt19937 rng(13);
  for (const auto& limits :
       {PointRowGrid::Limits{}, PointRowGrid::Limits{.max_dense_cells = 0, .max_table_rows = 0}}) {
    const auto layout = limits.max_dense_cells > 0 ? PointRowGrid::Layout::kDense
                                                   : PointRowGrid::Layout::kSparseRows;
    ExpectSameAsDense({{1, 2, 3}}, 0.5, limits, layout, rng);
    ExpectSameAsDense({{1, 2, 3}, {1, 2, 3}, {1.1f, 2, 3}}, 0.5, limits, layout, rng);
  }
}

TEST(PointRowGrid, LongRowsKeepTheirPointsInCellThenInputOrder) {
  // Rows of thousands of points over thousands of cells (sorted by counting) and rows of 200
  // points spread over thousands of cells (sorted by merging), each point's input index
  // stored as its weight: the stored order is by cell (z, y, x), then by input index, on 1
  // and 3 threads, in the dense and the row-table layouts.
  std::mt19937 rng(14);
  std::uniform_int_distribution<int> near(0, 7), far(0, 4000), yz(0, 2);
  std::vector<Point3f> points;
  std::vector<float> index;
  for (int i = 0; i < 30000; ++i) {
    const bool spread = i % 10 == 0;
    points.push_back({(spread ? far(rng) : near(rng)) + 0.5f, yz(rng) + 0.5f, yz(rng) + 0.5f});
    index.push_back(static_cast<float>(i));
  }
  for (int i = 0; i < 600; ++i) {
    points.push_back({far(rng) + 0.5f, 5.5f + i % 3, 5.5f});
    index.push_back(static_cast<float>(points.size() - 1));
  }
  for (const PointRowGrid::Limits& limits :
       {PointRowGrid::Limits{}, PointRowGrid::Limits{.max_dense_cells = 0}})
    for (int threads : {1, 3}) {
      const PointRowGrid grid(points, 1.0, threads, limits, index);
      ASSERT_EQ(grid.cell(), 1.0);
      std::array<int64_t, 4> last = {-1, -1, -1, -1};
      for (size_t s = 0; s < grid.num_points(); ++s) {
        // Cells of 1 from the box's low corner (0.5 on every axis): the floor of each coordinate.
        const std::array<int64_t, 4> key = {static_cast<int64_t>(grid.zs()[s]),
                                            static_cast<int64_t>(grid.ys()[s]),
                                            static_cast<int64_t>(grid.xs()[s]),
                                            static_cast<int64_t>(grid.ws()[s])};
        ASSERT_LT(last, key) << "slot " << s << ", " << threads << " threads";
        last = key;
      }
    }
}

}  // namespace
}  // namespace membrane

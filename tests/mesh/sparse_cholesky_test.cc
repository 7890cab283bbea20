// The sparse Cholesky factor (core/mesh/sparse_cholesky.h): it solves the systems the hole
// caps give it (a grid's bi-Laplacian with a fixed border) to rounding, against a dense
// elimination; it refuses matrices that are not positive definite, bad indices and factors
// over the size asked; the order of elimination does not change the answer.
#include "core/mesh/sparse_cholesky.h"

#include <cmath>
#include <algorithm>
#include <random>
#include <utility>
#include <vector>

#include "gtest/gtest.h"

namespace membrane {
namespace {

// The matrix as a dense n x n array, from its entries (each pair meant both ways).
std::vector<double> Dense(int n, const std::vector<SymmetricEntry>& entries) {
  std::vector<double> a(static_cast<size_t>(n) * n, 0.0);
  for (const SymmetricEntry& e : entries) {
    a[static_cast<size_t>(e.row) * n + e.col] += e.value;
    if (e.row != e.col) a[static_cast<size_t>(e.col) * n + e.row] += e.value;
  }
  return a;
}

// A x, per coordinate.
std::vector<Vec3d> Multiply(int n, const std::vector<double>& a, const std::vector<Vec3d>& x) {
  std::vector<Vec3d> y(n, Vec3d{0, 0, 0});
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int c = 0; c < 3; ++c) y[i][c] += a[static_cast<size_t>(i) * n + j] * x[j][c];
  return y;
}

// The free vertices of a side x side grid whose border ring is fixed: K = L D^-1 L of the
// 4-neighbour grid Laplacian restricted to them (the thin plate of hole_caps.cc), its
// positions the grid's, the entries given once per (w, pair) as the caps give them
// (repeated entries add up).
struct GridSystem {
  int n = 0;
  std::vector<Vec3d> positions;
  std::vector<SymmetricEntry> entries;
};

GridSystem GridBiLaplacian(int side) {
  GridSystem s;
  auto index = [&](int i, int j) -> int {
    if (i < 1 || j < 1 || i > side - 2 || j > side - 2) return -1;  // fixed
    return (i - 1) * (side - 2) + (j - 1);
  };
  s.n = (side - 2) * (side - 2);
  s.positions.resize(s.n);
  for (int i = 1; i < side - 1; ++i)
    for (int j = 1; j < side - 1; ++j) s.positions[index(i, j)] = {double(i), double(j), 0.0};
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      std::vector<std::pair<int, double>> stencil{{index(i, j), 0.0}};
      const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
      for (int k = 0; k < 4; ++k) {
        const int a = i + di[k], b = j + dj[k];
        if (a < 0 || b < 0 || a >= side || b >= side) continue;
        stencil.push_back({index(a, b), -1.0});
        stencil[0].second += 1.0;
      }
      const double inv = 1.0 / stencil[0].second;
      for (const auto& [a, ca] : stencil)
        for (const auto& [b, cb] : stencil)
          if (a >= 0 && b >= 0 && a <= b) s.entries.push_back({a, b, ca * cb * inv});
    }
  return s;
}

TEST(SparseCholesky, SolvesTheGridThinPlateAsDenseEliminationDoes) {
  const GridSystem s = GridBiLaplacian(22);  // 400 unknowns: dissected several levels deep
  const auto factor = SparseCholesky::Factor(s.n, s.positions, s.entries, int64_t{1} << 30);
  ASSERT_TRUE(factor.has_value());
  // Fill stays well under the dense triangle's n (n + 1) / 2 = 80,200 entries.
  EXPECT_LT(factor->entries(), 20000);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Vec3d> truth(s.n);
  for (Vec3d& t : truth) t = {u(rng), u(rng), u(rng)};
  const std::vector<double> a = Dense(s.n, s.entries);
  const std::vector<Vec3d> x = factor->Solve(Multiply(s.n, a, truth));
  ASSERT_EQ(x.size(), truth.size());
  double worst = 0;
  for (int i = 0; i < s.n; ++i)
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(x[i][c] - truth[i][c]));
  // The grid's bi-Laplacian has a condition number near 10^5 here: 1e-8 is rounding.
  EXPECT_LT(worst, 1e-8);
}

TEST(SparseCholesky, OrderOfEliminationDoesNotChangeTheAnswer) {
  const GridSystem s = GridBiLaplacian(14);
  // The same unknowns at scrambled positions: another nested-dissection order.
  std::vector<Vec3d> scrambled = s.positions;
  std::mt19937_64 rng(9);
  std::shuffle(scrambled.begin(), scrambled.end(), rng);
  const auto grid = SparseCholesky::Factor(s.n, s.positions, s.entries, int64_t{1} << 30);
  const auto other = SparseCholesky::Factor(s.n, scrambled, s.entries, int64_t{1} << 30);
  ASSERT_TRUE(grid.has_value());
  ASSERT_TRUE(other.has_value());
  std::vector<Vec3d> b(s.n);
  for (int i = 0; i < s.n; ++i) b[i] = {1.0, double(i % 7), -0.5 * i};
  const std::vector<Vec3d> x = grid->Solve(b), y = other->Solve(b);
  for (int i = 0; i < s.n; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(x[i][c], y[i][c], 1e-7 * (1 + std::abs(x[i][c])));
}

TEST(SparseCholesky, RefusesWhatItCannotFactor) {
  const std::vector<Vec3d> positions{{0, 0, 0}, {1, 0, 0}};
  // Indefinite: [[1, 2], [2, 1]].
  EXPECT_FALSE(SparseCholesky::Factor(2, positions, {{0, 0, 1.0}, {1, 1, 1.0}, {0, 1, 2.0}},
                                      100)
                   .has_value());
  // Singular: [[1, 1], [1, 1]].
  EXPECT_FALSE(SparseCholesky::Factor(2, positions, {{0, 0, 1.0}, {1, 1, 1.0}, {0, 1, 1.0}},
                                      100)
                   .has_value());
  // An index out of range, a value not finite, positions of another count.
  EXPECT_FALSE(SparseCholesky::Factor(2, positions, {{0, 2, 1.0}}, 100).has_value());
  EXPECT_FALSE(
      SparseCholesky::Factor(2, positions, {{0, 0, std::nan("")}, {1, 1, 1.0}}, 100).has_value());
  EXPECT_FALSE(SparseCholesky::Factor(3, positions, {{0, 0, 1.0}}, 100).has_value());
  // A factor larger than allowed: the grid's needs more than its unknowns' count.
  const GridSystem s = GridBiLaplacian(12);
  EXPECT_FALSE(SparseCholesky::Factor(s.n, s.positions, s.entries, s.n).has_value());
  EXPECT_TRUE(SparseCholesky::Factor(s.n, s.positions, s.entries, int64_t{1} << 30).has_value());
}

TEST(SparseCholesky, DiagonalMatrixIsItsOwnSolve) {
  const std::vector<Vec3d> positions{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  const auto f =
      SparseCholesky::Factor(3, positions, {{0, 0, 2.0}, {1, 1, 4.0}, {2, 2, 8.0}}, 100);
  ASSERT_TRUE(f.has_value());
  EXPECT_EQ(f->entries(), 3);
  const std::vector<Vec3d> x = f->Solve({{2, 4, 6}, {4, 8, 12}, {8, 16, 24}});
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(x[i][c], c + 1.0, 1e-12);
}

}  // namespace
}  // namespace membrane

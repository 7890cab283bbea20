#include "core/mesh/sparse_cholesky.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace membrane {
namespace {

// Compressed rows: row v's entries are items[start[v] .. start[v + 1]).
struct Graph {
  std::vector<int64_t> start;
  std::vector<int32_t> items;
};

// Below this many unknowns a part is eliminated as it comes: dissecting it saves no fill.
constexpr size_t kLeafSize = 32;

// Nested dissection by coordinate bisection: the part's unknowns split at the median of the
// longest side of their bounding box; the unknowns of the lower half with a neighbour in the
// upper half (the separator) are eliminated after both halves, so no fill crosses between
// them. Appends the part's elimination order to `order`; `label` holds each unknown's part.
void Dissect(std::vector<int32_t> part, const Graph& g, absl::Span<const Vec3d> positions,
             std::vector<int32_t>& label, int32_t& next_label, std::vector<int32_t>& order) {
  if (part.size() <= kLeafSize) {
    order.insert(order.end(), part.begin(), part.end());
    return;
  }
  Vec3d lo = positions[part[0]], hi = lo;
  for (int32_t v : part)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], positions[v][k]);
      hi[k] = std::max(hi[k], positions[v][k]);
    }
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (hi[k] - lo[k] > hi[axis] - lo[axis]) axis = k;
  const size_t half = part.size() / 2;
  std::nth_element(part.begin(), part.begin() + half, part.end(), [&](int32_t a, int32_t b) {
    return positions[a][axis] < positions[b][axis] ||
           (positions[a][axis] == positions[b][axis] && a < b);
  });
  const int32_t lower = next_label++, upper = next_label++;
  for (size_t i = 0; i < part.size(); ++i) label[part[i]] = i < half ? lower : upper;
  std::vector<int32_t> low, separator;
  for (size_t i = 0; i < half; ++i) {
    const int32_t v = part[i];
    bool touches = false;
    for (int64_t e = g.start[v]; e < g.start[v + 1] && !touches; ++e)
      touches = label[g.items[e]] == upper;
    (touches ? separator : low).push_back(v);
  }
  std::vector<int32_t> high(part.begin() + half, part.end());
  part.clear();
  part.shrink_to_fit();
  Dissect(std::move(low), g, positions, label, next_label, order);
  Dissect(std::move(high), g, positions, label, next_label, order);
  order.insert(order.end(), separator.begin(), separator.end());
}

// Row k of L's pattern (the columns j < k with L(k, j) != 0) in an order where each column
// comes before its ancestors in the elimination tree, in stack[top .. n); returns top. Walks
// up the tree from each entry of A's column k above the diagonal until a column already seen.
int32_t RowPattern(int32_t k, const Graph& upper, const std::vector<int32_t>& parent,
                   std::vector<int32_t>& mark, std::vector<int32_t>& path,
                   std::vector<int32_t>& stack) {
  int32_t top = static_cast<int32_t>(stack.size());
  mark[k] = k;
  for (int64_t e = upper.start[k]; e < upper.start[k + 1]; ++e) {
    int32_t i = upper.items[e];
    if (i >= k) continue;
    int32_t len = 0;
    for (; mark[i] != k; i = parent[i]) {
      path[len++] = i;
      mark[i] = k;
    }
    while (len > 0) stack[--top] = path[--len];
  }
  return top;
}

}  // namespace

std::optional<SparseCholesky> SparseCholesky::Factor(int32_t n, absl::Span<const Vec3d> positions,
                                                     absl::Span<const SymmetricEntry> entries,
                                                     int64_t max_entries) {
  if (n <= 0 || positions.size() != static_cast<size_t>(n)) return std::nullopt;
  for (const SymmetricEntry& e : entries)
    if (e.row < 0 || e.row >= n || e.col < 0 || e.col >= n || !std::isfinite(e.value))
      return std::nullopt;
  // The graph of A, off the diagonal, for the order.
  Graph g;
  g.start.assign(n + 1, 0);
  for (const SymmetricEntry& e : entries)
    if (e.row != e.col) {
      ++g.start[e.row + 1];
      ++g.start[e.col + 1];
    }
  for (int32_t v = 0; v < n; ++v) g.start[v + 1] += g.start[v];
  g.items.resize(g.start[n]);
  {
    std::vector<int64_t> fill(g.start.begin(), g.start.end() - 1);
    for (const SymmetricEntry& e : entries)
      if (e.row != e.col) {
        g.items[fill[e.row]++] = e.col;
        g.items[fill[e.col]++] = e.row;
      }
  }
  SparseCholesky f;
  f.n_ = n;
  {
    std::vector<int32_t> all(n);
    for (int32_t v = 0; v < n; ++v) all[v] = v;
    std::vector<int32_t> label(n, -1);
    int32_t next_label = 0;
    f.order_.reserve(n);
    Dissect(std::move(all), g, positions, label, next_label, f.order_);
  }
  std::vector<int32_t> rank(n);
  for (int32_t k = 0; k < n; ++k) rank[f.order_[k]] = k;
  // A's upper triangle by columns, in the elimination order: column j holds rows i <= j.
  Graph upper;
  std::vector<double> upper_values;
  upper.start.assign(n + 1, 0);
  for (const SymmetricEntry& e : entries)
    ++upper.start[std::max(rank[e.row], rank[e.col]) + 1];
  for (int32_t v = 0; v < n; ++v) upper.start[v + 1] += upper.start[v];
  upper.items.resize(upper.start[n]);
  upper_values.resize(upper.start[n]);
  {
    std::vector<int64_t> fill(upper.start.begin(), upper.start.end() - 1);
    for (const SymmetricEntry& e : entries) {
      const int32_t i = std::min(rank[e.row], rank[e.col]), j = std::max(rank[e.row], rank[e.col]);
      upper.items[fill[j]] = i;
      upper_values[fill[j]++] = e.value;
    }
  }
  // The elimination tree, with path compression through `ancestor`.
  std::vector<int32_t> parent(n, -1), ancestor(n, -1);
  for (int32_t k = 0; k < n; ++k)
    for (int64_t e = upper.start[k]; e < upper.start[k + 1]; ++e)
      for (int32_t i = upper.items[e]; i != -1 && i < k;) {
        const int32_t next = ancestor[i];
        ancestor[i] = k;
        if (next == -1) parent[i] = k;
        i = next;
      }
  // Column counts from the row patterns, then the factor's room.
  std::vector<int32_t> mark(n, -1), path(n), stack(n);
  std::vector<int64_t> count(n, 1);
  for (int32_t k = 0; k < n; ++k)
    for (int32_t t = RowPattern(k, upper, parent, mark, path, stack); t < n; ++t) ++count[stack[t]];
  f.start_.assign(n + 1, 0);
  for (int32_t j = 0; j < n; ++j) f.start_[j + 1] = f.start_[j] + count[j];
  if (f.start_[n] > max_entries) return std::nullopt;
  f.rows_.resize(f.start_[n]);
  f.values_.resize(f.start_[n]);
  // Up-looking: row k of L solves L(0:k, 0:k) l = A(0:k, k) over row k's pattern.
  std::fill(mark.begin(), mark.end(), -1);
  std::vector<int64_t> next(f.start_.begin(), f.start_.end() - 1);
  std::vector<double> x(n, 0.0);
  for (int32_t k = 0; k < n; ++k) {
    const int32_t top = RowPattern(k, upper, parent, mark, path, stack);
    for (int64_t e = upper.start[k]; e < upper.start[k + 1]; ++e)
      x[upper.items[e]] += upper_values[e];
    double d = x[k];
    x[k] = 0;
    for (int32_t t = top; t < n; ++t) {
      const int32_t i = stack[t];
      const double lki = x[i] / f.values_[f.start_[i]];
      x[i] = 0;
      for (int64_t p = f.start_[i] + 1; p < next[i]; ++p) x[f.rows_[p]] -= f.values_[p] * lki;
      d -= lki * lki;
      f.rows_[next[i]] = k;
      f.values_[next[i]++] = lki;
    }
    if (!(d > 0) || !std::isfinite(d)) return std::nullopt;
    f.rows_[next[k]] = k;
    f.values_[next[k]++] = std::sqrt(d);
  }
  return f;
}

std::vector<Vec3d> SparseCholesky::Solve(absl::Span<const Vec3d> b) const {
  std::vector<Vec3d> y(n_);
  for (int32_t k = 0; k < n_; ++k) y[k] = b[order_[k]];
  for (int32_t j = 0; j < n_; ++j) {
    const double inv = 1.0 / values_[start_[j]];
    for (int c = 0; c < 3; ++c) y[j][c] *= inv;
    for (int64_t p = start_[j] + 1; p < start_[j + 1]; ++p)
      for (int c = 0; c < 3; ++c) y[rows_[p]][c] -= values_[p] * y[j][c];
  }
  for (int32_t j = n_ - 1; j >= 0; --j) {
    for (int64_t p = start_[j] + 1; p < start_[j + 1]; ++p)
      for (int c = 0; c < 3; ++c) y[j][c] -= values_[p] * y[rows_[p]][c];
    const double inv = 1.0 / values_[start_[j]];
    for (int c = 0; c < 3; ++c) y[j][c] *= inv;
  }
  std::vector<Vec3d> x(n_);
  for (int32_t k = 0; k < n_; ++k) x[order_[k]] = y[k];
  return x;
}

}  // namespace membrane

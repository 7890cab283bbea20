#include "core/mesh/hole_caps.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/container/flat_hash_set.h"
#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "core/base/parallel_tasks.h"
#include "core/geometry/vec3.h"
#include "core/mesh/algebraic_sphere.h"
#include "core/mesh/corner_crease.h"
#include "core/mesh/gap_vertices.h"
#include "core/mesh/plane_fit.h"
#include "core/mesh/point_row_grid.h"
#include "core/mesh/self_intersection.h"
#include "core/mesh/sparse_cholesky.h"
#include "core/mesh/thin_plate_spline.h"

namespace membrane {
namespace {

constexpr int32_t kCancelPollVertices = 4096;

// Compressed rows: row v's entries are items[start[v] .. start[v + 1]).
struct Rows {
  std::vector<int32_t> start, items;
  int32_t size(int32_t v) const { return start[v + 1] - start[v]; }
  const int32_t* begin(int32_t v) const { return items.data() + start[v]; }
  const int32_t* end(int32_t v) const { return items.data() + start[v + 1]; }
};

// Each vertex's neighbours: in a closed oriented manifold every edge appears once in each
// direction, so the successors of v in its faces are its neighbours, each once. Also each
// vertex's faces.
void BuildRows(const TriangleMesh& mesh, Rows& neighbours, Rows& faces) {
  const int32_t nv = static_cast<int32_t>(mesh.vertices.size());
  neighbours.start.assign(nv + 1, 0);
  for (const auto& f : mesh.faces)
    for (int32_t v : f) ++neighbours.start[v + 1];
  for (int32_t v = 0; v < nv; ++v) neighbours.start[v + 1] += neighbours.start[v];
  faces.start = neighbours.start;
  neighbours.items.resize(neighbours.start[nv]);
  faces.items.resize(faces.start[nv]);
  std::vector<int32_t> fill(neighbours.start.begin(), neighbours.start.end() - 1);
  for (int32_t fi = 0; fi < static_cast<int32_t>(mesh.faces.size()); ++fi) {
    const auto& f = mesh.faces[fi];
    for (int k = 0; k < 3; ++k) {
      const int32_t slot = fill[f[k]]++;
      neighbours.items[slot] = f[(k + 1) % 3];
      faces.items[slot] = fi;
    }
  }
}

// A position or a direction in a solve: x and y as one two-lane vector, z alone. Each lane
// computes what the same operation on its coordinate alone computes (no contraction into
// fused multiply-adds on this target), so the solve's arithmetic is Vec3d's, two coordinates
// an instruction.
using Pair = double __attribute__((vector_size(16), aligned(8)));
struct Lanes {
  Pair xy;
  double z;
  double operator[](int k) const { return k < 2 ? xy[k] : z; }
  Lanes& operator+=(const Lanes& o) {
    xy += o.xy;
    z += o.z;
    return *this;
  }
  Lanes& operator-=(const Lanes& o) {
    xy -= o.xy;
    z -= o.z;
    return *this;
  }
  friend Lanes operator*(double s, const Lanes& a) { return {s * a.xy, s * a.z}; }
  friend Lanes operator*(const Lanes& a, double s) { return {a.xy * s, a.z * s}; }
  friend Lanes operator*(const Lanes& a, const Lanes& b) { return {a.xy * b.xy, a.z * b.z}; }
  friend Lanes operator+(const Lanes& a, const Lanes& b) { return {a.xy + b.xy, a.z + b.z}; }
  // |a| and the larger of a and b lane by lane, as std::abs and std::max on each.
  friend Lanes Abs(const Lanes& a) { return {a.xy < 0 ? -a.xy : a.xy, std::abs(a.z)}; }
  friend Lanes Max(const Lanes& a, const Lanes& b) {
    return {a.xy < b.xy ? b.xy : a.xy, std::max(a.z, b.z)};
  }
};

// Solve reads the neighbours of a vertex with at most this many as a row of fixed length.
constexpr int32_t kRowWidth = 8;

// The part of the mesh a solve over `free` reads, renumbered: the free vertices first (local
// 0..n-1, in the order of `free`), then the other vertices within one ring of them (n..m-1),
// then those within two rings (m..size-1). Rows hold the local neighbours of the first m, in
// the mesh's order, and each one's degree in the whole mesh: the Laplacian of a vertex within
// one ring reads only local vertices, so the solve never touches a whole-mesh array.
struct LocalSystem {
  std::vector<int32_t> vertex;  // local -> mesh
  int32_t n = 0, m = 0;
  Rows nb;                      // rows of the first m local vertices
};

// Local numbers by mesh vertex (-1: none yet), in an array over the mesh or a hash map.
struct ArrayNumbers {
  std::vector<int32_t> local;
  int32_t& operator[](int32_t v) { return local[v]; }
};
struct HashNumbers {
  absl::flat_hash_map<int32_t, int32_t> local;
  int32_t& operator[](int32_t v) { return local.try_emplace(v, -1).first->second; }
};

template <typename Numbers>
LocalSystem LocalizeWith(const Rows& nb, const std::vector<int32_t>& free, bool two_rings,
                         Numbers& local) {
  LocalSystem s;
  auto add = [&](int32_t v) {
    if (local[v] >= 0) return;
    local[v] = static_cast<int32_t>(s.vertex.size());
    s.vertex.push_back(v);
  };
  for (int32_t v : free) add(v);
  s.n = static_cast<int32_t>(s.vertex.size());
  for (int32_t i = 0; i < s.n; ++i)
    for (const int32_t* u = nb.begin(s.vertex[i]); u != nb.end(s.vertex[i]); ++u) add(*u);
  s.m = two_rings ? static_cast<int32_t>(s.vertex.size()) : s.n;
  for (int32_t i = 0; i < s.m; ++i)
    for (const int32_t* u = nb.begin(s.vertex[i]); u != nb.end(s.vertex[i]); ++u) add(*u);
  s.nb.start.assign(s.m + 1, 0);
  for (int32_t i = 0; i < s.m; ++i) s.nb.start[i + 1] = s.nb.start[i] + nb.size(s.vertex[i]);
  s.nb.items.resize(s.nb.start[s.m]);
  int32_t* out = s.nb.items.data();
  for (int32_t i = 0; i < s.m; ++i)
    for (const int32_t* u = nb.begin(s.vertex[i]); u != nb.end(s.vertex[i]); ++u)
      *out++ = local[*u];
  return s;
}

LocalSystem Localize(const Rows& nb, const std::vector<int32_t>& free, bool two_rings) {
  // The same numbers either way. An array over the mesh is a pass of 4 bytes a vertex, a
  // hash map an insertion for each vertex of the region's rings: the array for a large
  // region (a 10M-point scan's largest cap: 2M insertions a solve), the map for a small one
  // (that scan's mesh makes the array 28 MB, and its caps take a hundred small solves).
  const size_t vertices = nb.start.size() - 1;
  if (free.size() * 64 >= vertices) {
    ArrayNumbers numbers{std::vector<int32_t>(vertices, -1)};
    return LocalizeWith(nb, free, two_rings, numbers);
  }
  HashNumbers numbers;
  numbers.local.reserve(free.size() * 3);
  return LocalizeWith(nb, free, two_rings, numbers);
}

// Conjugate gradients over the free vertices, every other vertex fixed, for the graph
// Laplacian (L x)_v = deg_v x_v - sum of the neighbours' x: the harmonic map L_ff x_f =
// -L_fc x_c, or the thin plate K_ff x_f = -K_fc x_c with K = L D^-1 L (the minimum of the sum
// of |L x_v|^2 / deg_v; both symmetric positive definite on regions with a fixed neighbour).
// Jacobi-preconditioned, each coordinate on its own, from the positions in `x` (every vertex;
// the free ones are updated). Stops after `max_iterations` or once no step moves a vertex by
// more than `tolerance`. Returns the iterations run, or -1 when `cancel` fired. Works on the
// region and its two rings renumbered (LocalSystem): memory and time in the region's size.
// A region of `min_split` vertices or more has its products, updates and dot products on
// `threads` (<= 1: the calling thread); its dot products are summed over blocks of min_split
// free vertices, each in vertex order, then over the blocks in their order (a smaller region,
// or min_split <= 1: in vertex order), so the result is the same bits for any count.
int Solve(bool thin_plate, const Rows& mesh_nb, const std::vector<int32_t>& free,
          std::vector<Vec3d>& x, int max_iterations, double tolerance, const CancelToken& cancel,
          int threads = 1, int64_t min_split = 0) {
  const LocalSystem sys = Localize(mesh_nb, free, thin_plate);
  const Rows& nb = sys.nb;
  const size_t n = static_cast<size_t>(sys.n);
  const int32_t m = sys.m;
  const size_t size = sys.vertex.size();
  std::vector<double> degree(static_cast<size_t>(m)), inv_degree(static_cast<size_t>(m));
  for (int32_t v = 0; v < m; ++v) {
    degree[v] = static_cast<double>(nb.size(v));
    inv_degree[v] = 1.0 / nb.size(v);
  }
  // Rows of up to kRowWidth neighbours, padded with the index of a zero entry (local `size`,
  // one past the last vertex): subtracting +0 leaves a sum as it was, bit for bit, and a
  // row of fixed length costs no mispredicted loop exit. Longer rows are read from `nb`.
  const int32_t zero = static_cast<int32_t>(size);
  std::vector<int32_t> padded(static_cast<size_t>(m) * kRowWidth, zero);
  std::vector<char> long_row(static_cast<size_t>(m), 0);
  for (int32_t v = 0; v < m; ++v) {
    if (nb.size(v) > kRowWidth) {
      long_row[v] = 1;
      continue;
    }
    std::copy(nb.begin(v), nb.end(v), padded.begin() + static_cast<ptrdiff_t>(v) * kRowWidth);
  }
  // out = L y at local vertex v (y[size] is zero).
  auto laplacian = [&](int32_t v, const Lanes* y, Lanes& out) {
    Lanes sum = degree[v] * y[v];
    if (long_row[v]) {
      for (const int32_t* u = nb.begin(v); u != nb.end(v); ++u) sum -= y[*u];
    } else {
      const int32_t* row = padded.data() + static_cast<ptrdiff_t>(v) * kRowWidth;
      for (int k = 0; k < kRowWidth; ++k) sum -= y[row[k]];
    }
    out = sum;
  };
  // D^-1 L y over the free vertices and their ring (local 0..m-1), for K y.
  std::vector<Lanes> scaled(thin_plate ? size + 1 : 0, Lanes{});
  // Ranges of the free vertices and of the free ones with their ring, one task each: every
  // vertex's product and update reads only what the step before wrote.
  const int workers = static_cast<int64_t>(n) >= min_split ? threads : 1;
  const TaskRanges free_ranges = TaskRanges::Split(static_cast<int64_t>(n), workers, 2);
  const TaskRanges ring_ranges = TaskRanges::Split(m, workers, 2);
  auto for_ranges = [&](const TaskRanges& ranges, auto&& body) {
    RunTasks(workers, ranges.tasks,
             [&](int, int64_t t) { body(t, ranges.begin(t), ranges.end(t)); });
  };
  // The free vertices' blocks, a few to a task: sum_blocks(body) runs body(block, begin, end)
  // on each block's vertices [begin, end) and returns the sum of what the calls return, in
  // block order. A pass over the vectors then sums as it goes, on every thread, instead of
  // being read again on the calling thread. Blocks of min_split vertices where the solve
  // splits at min_split > 1; otherwise the sums go in vertex order, which blocks of one vertex
  // give as well as one block: a vertex a block where threads share the passes, one block
  // where the calling thread runs them.
  const int64_t count = static_cast<int64_t>(n);
  int64_t block = std::max<int64_t>(count, 1);
  if (count >= min_split && min_split > 1) {
    block = min_split;
  } else if (workers > 1) {
    block = 1;
  }
  const int64_t blocks = (count + block - 1) / block;
  const TaskRanges block_ranges = TaskRanges::Split(blocks, workers, 2);
  std::vector<Lanes> block_sums(static_cast<size_t>(blocks));
  auto sum_blocks = [&](auto&& body) {
    for_ranges(block_ranges, [&](int64_t, int64_t first, int64_t last) {
      for (int64_t b = first; b < last; ++b) {
        block_sums[b] = body(b, b * block, std::min<int64_t>((b + 1) * block, n));
      }
    });
    Lanes sum{};
    for (const Lanes& partial : block_sums) sum += partial;
    return sum;
  };
  // out = K y over the free vertices; returns y . out.
  auto apply = [&](const std::vector<Lanes>& y, std::vector<Lanes>& out) {
    const Lanes* in = y.data();
    if (thin_plate) {
      for_ranges(ring_ranges, [&](int64_t, int64_t begin, int64_t end) {
        for (int32_t v = static_cast<int32_t>(begin); v < end; ++v) {
          laplacian(v, y.data(), scaled[v]);
          scaled[v] = inv_degree[v] * scaled[v];
        }
      });
      in = scaled.data();
    }
    return sum_blocks([&](int64_t, int64_t begin, int64_t end) {
      Lanes dot{};
      for (int32_t i = static_cast<int32_t>(begin); i < end; ++i) {
        laplacian(i, in, out[i]);
        dot += y[i] * out[i];
      }
      return dot;
    });
  };
  std::vector<double> inv_diag(n);
  for (size_t i = 0; i < n; ++i) {
    const int32_t v = static_cast<int32_t>(i);
    double d = nb.size(v);
    if (thin_plate)
      for (const int32_t* u = nb.begin(v); u != nb.end(v); ++u) d += 1.0 / nb.size(*u);
    inv_diag[i] = 1.0 / d;
  }
  std::vector<Lanes> y(size + 1, Lanes{});
  for (size_t i = 0; i < size; ++i) {
    const Vec3d& v = x[sys.vertex[i]];
    y[i] = Lanes{Pair{v[0], v[1]}, v[2]};
  }
  // The search direction per local vertex, zero off the free ones (the first n).
  std::vector<Lanes> p(size + 1, Lanes{});
  std::vector<Lanes> r(n), z(n), q(n);
  apply(y, r);
  Lanes rz = sum_blocks([&](int64_t, int64_t begin, int64_t end) {
    Lanes sum{};
    for (int64_t i = begin; i < end; ++i) {
      r[i] = -1.0 * r[i];
      z[i] = inv_diag[i] * r[i];
      p[i] = z[i];
      sum += r[i] * z[i];
    }
    return sum;
  });
  std::vector<Lanes> block_largest(static_cast<size_t>(blocks));
  int it = 0;
  while (it < max_iterations) {
    if (cancel.cancelled()) return -1;
    ++it;
    const Lanes pq = apply(p, q);
    double a[3];
    for (int k = 0; k < 3; ++k) a[k] = pq[k] > 0 ? rz[k] / pq[k] : 0.0;
    const Lanes alpha{Pair{a[0], a[1]}, a[2]};
    // The largest step per block: a maximum, the same whatever the blocks.
    const Lanes rz_next = sum_blocks([&](int64_t b, int64_t begin, int64_t end) {
      Lanes largest{}, sum{};
      for (int64_t i = begin; i < end; ++i) {
        const Lanes step = alpha * p[i];
        y[i] += step;
        largest = Max(largest, Abs(step));
        r[i] -= alpha * q[i];
        z[i] = r[i] * inv_diag[i];
        sum += r[i] * z[i];
      }
      block_largest[b] = largest;
      return sum;
    });
    Lanes largest{};
    for (const Lanes& l : block_largest) largest = Max(largest, l);
    if (std::max({largest[0], largest[1], largest[2]}) <= tolerance) break;
    double b[3];
    for (int k = 0; k < 3; ++k) b[k] = rz[k] > 0 ? rz_next[k] / rz[k] : 0.0;
    const Lanes beta{Pair{b[0], b[1]}, b[2]};
    for_ranges(free_ranges, [&](int64_t, int64_t begin, int64_t end) {
      for (int64_t i = begin; i < end; ++i) p[i] = z[i] + beta * p[i];
    });
    rz = rz_next;
  }
  for (size_t i = 0; i < n; ++i) x[sys.vertex[i]] = Vec3d{y[i][0], y[i][1], y[i][2]};
  return it;
}

// The factor of a plate solved exactly holds at most this many entries (12 bytes each); a
// larger cap is solved by conjugate gradients (Solve) to the tolerance asked.
constexpr int64_t kMaxFactorEntries = int64_t{4} << 20;

// The thin plate over the free vertices solved exactly, every other vertex fixed: K_ff x_f =
// -K_fc x_c (Solve's system) by a sparse Cholesky factor (sparse_cholesky.h), the positions in
// `x` updated. false, with `x` unchanged, when the factor would hold more than `max_entries`
// or fails.
bool SolveExactly(const Rows& mesh_nb, const std::vector<int32_t>& free, std::vector<Vec3d>& x,
                  int64_t max_entries = kMaxFactorEntries) {
  // The factor's entries a row grow with the cap (24 at 1,726 unknowns, 84 at 11,214): past
  // max_entries / 32 unknowns it cannot fit, and is not built.
  if (static_cast<int64_t>(free.size()) * 32 > max_entries) return false;
  const LocalSystem sys = Localize(mesh_nb, free, /*two_rings=*/true);
  const Rows& nb = sys.nb;
  const int32_t n = sys.n;
  // K = L D^-1 L: row w of L (deg_w at w, -1 at each neighbour) pairs its free entries.
  std::vector<SymmetricEntry> entries;
  std::vector<Vec3d> b(n, Vec3d{0, 0, 0});
  std::vector<std::pair<int32_t, double>> stencil;
  for (int32_t w = 0; w < sys.m; ++w) {
    const double inv = 1.0 / nb.size(w);
    stencil.assign(1, {w, static_cast<double>(nb.size(w))});
    for (const int32_t* u = nb.begin(w); u != nb.end(w); ++u) stencil.push_back({*u, -1.0});
    // The fixed part of L x at w moves to the right-hand side.
    Vec3d fixed{0, 0, 0};
    for (const auto& [v, c] : stencil)
      if (v >= n) fixed = fixed + c * x[sys.vertex[v]];
    for (const auto& [a, ca] : stencil) {
      if (a >= n) continue;
      b[a] = b[a] - (ca * inv) * fixed;
      for (const auto& [c, cc] : stencil)
        if (c < n && a <= c) entries.push_back({a, c, ca * cc * inv});
    }
  }
  std::vector<Vec3d> positions(n);
  for (int32_t i = 0; i < n; ++i) positions[i] = x[sys.vertex[i]];
  const auto factor = SparseCholesky::Factor(n, positions, entries, max_entries);
  if (!factor) return false;
  const std::vector<Vec3d> solved = factor->Solve(b);
  for (int32_t i = 0; i < n; ++i)
    if (!std::isfinite(solved[i][0]) || !std::isfinite(solved[i][1]) ||
        !std::isfinite(solved[i][2]))
      return false;
  for (int32_t i = 0; i < n; ++i) x[sys.vertex[i]] = solved[i];
  return true;
}

// A start near the converged thin plate for a region too large for the factor: the region's
// vertices and the fixed ones within 4 s + 2 rings of it clustered by cells of s voxels (edge
// `l`; s the least whole number with at most `max_clusters` cells' worth of free vertices,
// s^2 of them a cell), a cell's free vertices one cluster and its fixed ones another, the
// clusters joined where a mesh edge joins their vertices, each at the mean of its vertices,
// and the thin plate of that graph over the free clusters solved exactly (SolveExactly). Each
// free vertex then moves by its cluster's move.
// Conjugate gradients on the bi-Laplacian need iterations growing with the square of the
// region's width: from this start they have left only the clusters' steps to smooth, a few
// cells wide. False, with `x` unchanged, where the coarse plate cannot be solved.
bool CoarsePlateStart(const Rows& nb, const std::vector<int32_t>& free, double l,
                      int64_t max_clusters, std::vector<Vec3d>& x) {
  const int s = static_cast<int>(std::ceil(
      std::sqrt(static_cast<double>(free.size()) / static_cast<double>(max_clusters))));
  // The region, then the fixed vertices ring by ring: the coarse plate reads two rings of
  // clusters around its free ones, and a cluster is at most about 2 s edges across.
  absl::flat_hash_map<int32_t, int32_t> local;  // mesh vertex -> index in `vertex`
  std::vector<int32_t> vertex(free.begin(), free.end());
  local.reserve(free.size() * 2);
  for (size_t i = 0; i < free.size(); ++i) local.emplace(free[i], static_cast<int32_t>(i));
  const size_t n_free = free.size();
  size_t ring_begin = 0;
  for (int ring = 0; ring < 4 * s + 2; ++ring) {
    const size_t ring_end = vertex.size();
    for (size_t i = ring_begin; i < ring_end; ++i)
      for (const int32_t* u = nb.begin(vertex[i]); u != nb.end(vertex[i]); ++u)
        if (local.try_emplace(*u, static_cast<int32_t>(vertex.size())).second)
          vertex.push_back(*u);
    ring_begin = ring_end;
  }
  // Clusters by cell, the free vertices of a cell apart from its fixed ones: a fixed vertex
  // (the rim's, or one a seen point holds) then fixes its cluster without holding the free
  // vertices beside it.
  struct Cluster {
    Vec3d sum{0, 0, 0};
    int32_t count = 0;
    bool free = false;
  };
  absl::flat_hash_map<std::array<int64_t, 4>, int32_t> by_cell;
  std::vector<Cluster> clusters;
  std::vector<int32_t> cluster_of(vertex.size());
  const double cell = s * l;
  for (size_t i = 0; i < vertex.size(); ++i) {
    const Vec3d& p = x[vertex[i]];
    const bool is_free = i < n_free;
    const std::array<int64_t, 4> key = {static_cast<int64_t>(std::floor(p[0] / cell)),
                                        static_cast<int64_t>(std::floor(p[1] / cell)),
                                        static_cast<int64_t>(std::floor(p[2] / cell)), is_free};
    const auto [it, fresh] = by_cell.try_emplace(key, static_cast<int32_t>(clusters.size()));
    if (fresh) clusters.push_back(Cluster{.free = is_free});
    Cluster& c = clusters[it->second];
    cluster_of[i] = it->second;
    c.sum = c.sum + p;
    ++c.count;
  }
  // The clusters' graph, free clusters first (the coarse system's unknowns).
  const int32_t nc = static_cast<int32_t>(clusters.size());
  std::vector<int32_t> order(nc), coarse_of(nc);
  for (int32_t c = 0; c < nc; ++c) order[c] = c;
  std::stable_partition(order.begin(), order.end(),
                        [&](int32_t c) { return clusters[c].free; });
  for (int32_t k = 0; k < nc; ++k) coarse_of[order[k]] = k;
  std::vector<std::pair<int32_t, int32_t>> edges;
  for (size_t i = 0; i < vertex.size(); ++i)
    for (const int32_t* u = nb.begin(vertex[i]); u != nb.end(vertex[i]); ++u) {
      const auto it = local.find(*u);
      if (it == local.end()) continue;
      const int32_t a = coarse_of[cluster_of[i]], b = coarse_of[cluster_of[it->second]];
      if (a != b) edges.emplace_back(a, b);
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  Rows coarse;
  coarse.start.assign(nc + 1, 0);
  for (const auto& [a, b] : edges) ++coarse.start[a + 1];
  for (int32_t c = 0; c < nc; ++c) coarse.start[c + 1] += coarse.start[c];
  coarse.items.resize(edges.size());
  for (size_t e = 0; e < edges.size(); ++e) coarse.items[e] = edges[e].second;
  std::vector<Vec3d> positions(nc);
  std::vector<int32_t> unknowns;
  for (int32_t k = 0; k < nc; ++k) {
    const Cluster& c = clusters[order[k]];
    positions[k] = (1.0 / c.count) * c.sum;
    if (c.free) unknowns.push_back(k);
  }
  // Free clusters with no fixed cluster joined to them make a singular plate, which the factor
  // refuses (false): the caller then solves from the start it had.
  if (unknowns.empty()) return false;
  const std::vector<Vec3d> start = positions;
  // 128 entries a cluster: the factor of 38,020 clusters held 75 a row.
  if (!SolveExactly(coarse, unknowns, positions, 128 * max_clusters)) return false;
  for (size_t i = 0; i < n_free; ++i) {
    const int32_t k = coarse_of[cluster_of[i]];
    x[vertex[i]] = x[vertex[i]] + (positions[k] - start[k]);
  }
  return true;
}

// The thin plate over the free vertices to convergence: exactly (SolveExactly) where the
// factor fits, else by Solve to `tolerance` in at most `max_iterations`, or at most
// `coarse_iterations` from the coarse plate (CoarsePlateStart: voxels of edge `l`, at most
// `coarse_clusters` clusters) where that one is solved. Returns the conjugate-gradient
// iterations run (0 when solved exactly), or -1 when `cancel` fired. `threads` and
// `min_split` as Solve's.
int SolveConverged(const Rows& nb, const std::vector<int32_t>& free, std::vector<Vec3d>& x,
                   int max_iterations, double tolerance, const CancelToken& cancel,
                   int threads, int64_t min_split, double l, int64_t coarse_clusters,
                   int coarse_iterations) {
  if (cancel.cancelled()) return -1;
  if (max_iterations > 0 && SolveExactly(nb, free, x)) return 0;
  if (max_iterations > 0 && CoarsePlateStart(nb, free, l, coarse_clusters, x))
    max_iterations = std::min(max_iterations, coarse_iterations);
  return Solve(true, nb, free, x, max_iterations, tolerance, cancel, threads, min_split);
}

// Sum of the face normals (twice the areas) around v: its outward direction.
Vec3d VertexNormal(const TriangleMesh& mesh, const Rows& star, int32_t v) {
  Vec3d n{0, 0, 0};
  for (const int32_t* f = star.begin(v); f != star.end(v); ++f) {
    const auto& t = mesh.faces[*f];
    n = n + TriangleNormal(ToVec3d(mesh.vertices[t[0]]), ToVec3d(mesh.vertices[t[1]]),
                           ToVec3d(mesh.vertices[t[2]]));
  }
  return n;
}

// The fixed vertices within `rings` rings of the region, breadth first, sorted: the band of
// the surface around the cap.
std::vector<int32_t> Band(const Rows& nb, const std::vector<int32_t>& region,
                          const std::vector<char>& free, int rings) {
  std::vector<int32_t> band;
  absl::flat_hash_set<int32_t> visited;
  std::vector<int32_t> frontier = region;
  for (int32_t v : region) visited.insert(v);
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<int32_t> next;
    for (int32_t v : frontier)
      for (const int32_t* u = nb.begin(v); u != nb.end(v); ++u)
        if (!free[*u] && visited.insert(*u).second) next.push_back(*u);
    band.insert(band.end(), next.begin(), next.end());
    frontier = std::move(next);
  }
  std::sort(band.begin(), band.end());
  return band;
}

// How a cap starts its thin plate: from the spline, or from the harmonic map where the rim is
// no height field, in its plane or wrapped around a swallowed part (HoleCapOptions::wrap_rms).
enum class CapStart { kSpline, kHarmonic, kWrapped };

// The cap of one region: the thin-plate spline over the rim's plane through the samples, at
// the harmonic positions `x` of its vertices (in voxels); written into `x`. Another start
// when the spline cannot shape it (x then unchanged; see CapHoles).
CapStart ShapeCap(const TriangleMesh& mesh, const Rows& nb, const Rows& star,
                  const std::vector<int32_t>& region, const std::vector<char>& free, double l,
                  const HoleCapOptions& options, std::vector<Vec3d>& x) {
  const std::vector<int32_t> samples = Band(nb, region, free, options.sample_rings);
  if (samples.size() < 3) return CapStart::kHarmonic;
  const size_t stride = (samples.size() + options.max_samples - 1) / options.max_samples;
  // In voxels, relative to the first sample: small, well-conditioned numbers.
  const Vec3d origin = ToVec3d(mesh.vertices[samples[0]]);
  auto local = [&](const Vec3d& p) { return (1.0 / l) * (p - origin); };
  PlaneFitAccumulator acc;
  Vec3d outward{0, 0, 0};
  for (size_t i = 0; i < samples.size(); i += stride) {
    acc.Add(local(ToVec3d(mesh.vertices[samples[i]])), 1.0);
    outward = outward + Normalized(VertexNormal(mesh, star, samples[i]));
  }
  const auto plane = acc.Fit();
  if (!plane) return CapStart::kHarmonic;
  const Vec3d n = Dot(plane->normal, outward) < 0 ? -1.0 * plane->normal : plane->normal;
  const Vec3d t1 = Normalized(std::abs(n[0]) < 0.9 ? Cross(n, Vec3d{1, 0, 0})
                                                   : Cross(n, Vec3d{0, 1, 0}));
  const Vec3d t2 = Cross(n, t1);
  std::vector<Vec3d> heights;
  bool height_field = true;
  double squares = 0;  // of the heights: the samples' spread off their plane
  for (size_t i = 0; i < samples.size(); i += stride) {
    const Vec3d normal = Normalized(VertexNormal(mesh, star, samples[i]));
    height_field = height_field && Dot(normal, n) > options.min_rim_cosine;
    const Vec3d p = local(ToVec3d(mesh.vertices[samples[i]])) - plane->centroid;
    heights.push_back({Dot(p, t1), Dot(p, t2), Dot(p, n)});
    squares += heights.back()[2] * heights.back()[2];
  }
  if (!height_field)
    return std::sqrt(squares / static_cast<double>(heights.size())) > options.wrap_rms
               ? CapStart::kWrapped
               : CapStart::kHarmonic;
  const auto spline = ThinPlateSpline::Fit(heights, options.smoothing);
  if (!spline) return CapStart::kHarmonic;
  for (int32_t v : region) {
    const Vec3d p = local(x[v]) - plane->centroid;
    const double u = Dot(p, t1), w = Dot(p, t2);
    x[v] = origin + l * (plane->centroid + u * t1 + w * t2 + (*spline)(u, w) * n);
  }
  return CapStart::kSpline;
}

// The algebraic sphere of the band around a region (the fixed vertices within sample_rings
// rings, with their normals), in voxels, where it describes the band: the band's vertices lie
// within options.sphere_band_fit voxels of it on average. nullopt elsewhere.
std::optional<AlgebraicSphere> BandSphere(const TriangleMesh& mesh, const Rows& nb,
                                          const Rows& star, const std::vector<int32_t>& region,
                                          const std::vector<char>& free, double l,
                                          const HoleCapOptions& options) {
  const std::vector<int32_t> band = Band(nb, region, free, options.sample_rings);
  std::vector<Vec3d> positions, normals;
  for (int32_t v : band) {
    positions.push_back((1.0 / l) * ToVec3d(mesh.vertices[v]));
    normals.push_back(Normalized(VertexNormal(mesh, star, v)));
  }
  const auto sphere = AlgebraicSphere::Fit(positions, normals);
  if (!sphere) return std::nullopt;
  double sum = 0;
  for (const Vec3d& p : positions) sum += sphere->Distance(p);
  if (!(sum <= options.sphere_band_fit * static_cast<double>(positions.size())))
    return std::nullopt;
  return sphere;
}

// A rim around a post or the edge of a thin part whose end the hole swallowed: its axis, from
// the band's centroid toward the middle of the cap (unit), and its radius, the band's mean
// distance from that axis in voxels.
struct Tube {
  Vec3d axis;
  double radius = 0;
};

// The tube of a rim (wrapped, or a spline cap's) around a post or the edge of a thin part
// whose end the hole swallowed (HoleCapOptions::tube_flatness, tube_lead), the cap's middle
// read from its vertices in the gap (`gap`, at their positions in `x`). nullopt where the
// band's normals are not square to the axis (no post), or the cap lies too little ahead of the
// band along it.
std::optional<Tube> FindTube(const TriangleMesh& mesh, const Rows& nb, const Rows& star,
                             const std::vector<int32_t>& region, const std::vector<char>& free,
                             const std::vector<char>& gap, const std::vector<Vec3d>& x, double l,
                             const HoleCapOptions& options) {
  const std::vector<int32_t> band = Band(nb, region, free, options.sample_rings);
  if (band.size() < 3 || region.empty()) return std::nullopt;
  const Vec3d origin = ToVec3d(mesh.vertices[band[0]]);
  std::vector<Vec3d> positions;
  Vec3d centroid{0, 0, 0};
  for (int32_t v : band) {
    positions.push_back((1.0 / l) * (ToVec3d(mesh.vertices[v]) - origin));
    centroid = centroid + positions.back();
  }
  const double count = static_cast<double>(band.size());
  centroid = (1.0 / count) * centroid;
  // The cap's middle: its vertices in the gap (the rim's rings lie along the band).
  Vec3d cap{0, 0, 0};
  int inside = 0;
  for (int32_t v : region)
    if (gap[v]) {
      cap = cap + (1.0 / l) * (x[v] - origin);
      ++inside;
    }
  if (inside == 0) return std::nullopt;
  const Vec3d ahead = (1.0 / inside) * cap - centroid;
  const double lead = Norm(ahead);
  if (!(lead > 0)) return std::nullopt;
  const Vec3d axis = (1.0 / lead) * ahead;
  double off_square = 0, radius = 0;
  for (size_t i = 0; i < band.size(); ++i) {
    const Vec3d n = Normalized(VertexNormal(mesh, star, band[i]));
    off_square += Dot(n, axis) * Dot(n, axis);
    const Vec3d d = positions[i] - centroid;
    radius += Norm(d - Dot(d, axis) * axis);
  }
  radius /= count;
  if (!(off_square <= options.tube_flatness * count) || !(lead >= options.tube_lead * radius))
    return std::nullopt;
  return Tube{axis, radius};
}

// Sweeps a cap on past its rim by `length` (model units): each vertex of the first fixed ring
// around the region points into the hole along its tangent plane (toward the middle of the
// cap, the normal part taken off: down a post's walls, along a thin part's faces; or, given
// `axis`, along that axis with the normal part taken off, a unit step on a wall parallel to
// it and shorter where the wall turns away); the harmonic map of those directions over the
// region carries them to the cap's vertices, and the vertices k rings from the fixed ones
// move by min(k / rim_rings, 1) of `length` along theirs: the first rim_rings rings stretch
// along the walls, the rest of the cap moves whole (where the directions disagree, their
// harmonic mean is shorter). False when `cancel` fired (x then unchanged). `field` is
// scratch of x.size() zero vectors, zero again on return: a sweep reads and writes only the
// region and its ring, and a 10M-point scan's dozens of swept caps would otherwise each fill
// 170 MB.
bool SweepCap(const TriangleMesh& mesh, const Rows& nb, const Rows& star,
              const std::vector<int32_t>& region, const std::vector<char>& free,
              const std::vector<char>& gap, double length, const std::optional<Vec3d>& axis,
              const HoleCapOptions& options, std::vector<Vec3d>& x,
              std::vector<Vec3d>& field, const CancelToken& cancel) {
  Vec3d middle{0, 0, 0};
  int inside = 0;
  for (int32_t v : region)
    if (gap[v]) {
      middle = middle + x[v];
      ++inside;
    }
  middle = (1.0 / std::max(inside, 1)) * middle;
  auto clear_field = [&] {
    for (int32_t v : region) {
      field[v] = Vec3d{0, 0, 0};
      for (const int32_t* u = nb.begin(v); u != nb.end(v); ++u) field[*u] = Vec3d{0, 0, 0};
    }
  };
  absl::flat_hash_map<int32_t, int> rings;
  std::vector<int32_t> frontier;
  for (int32_t v : region)
    for (const int32_t* u = nb.begin(v); u != nb.end(v); ++u)
      if (!free[*u]) {
        if (!rings.contains(v)) frontier.push_back(v);
        rings[v] = 1;
        const Vec3d n = Normalized(VertexNormal(mesh, star, *u));
        if (axis) {
          field[*u] = *axis - Dot(*axis, n) * n;
        } else {
          const Vec3d to = middle - ToVec3d(mesh.vertices[*u]);
          field[*u] = Normalized(to - Dot(to, n) * n);
        }
      }
  for (int ring = 2; !frontier.empty(); ++ring) {
    std::vector<int32_t> next;
    for (int32_t v : frontier)
      for (const int32_t* u = nb.begin(v); u != nb.end(v); ++u)
        if (free[*u] && !rings.contains(*u)) {
          rings[*u] = ring;
          next.push_back(*u);
        }
    frontier = std::move(next);
  }
  std::vector<int32_t> sorted = region;
  std::sort(sorted.begin(), sorted.end());
  // Unit directions: `tolerance` read as a share of one.
  if (Solve(false, nb, sorted, field, options.harmonic_iterations, options.tolerance, cancel) < 0) {
    clear_field();
    return false;
  }
  const double ramp = std::max(1, options.rim_rings);
  for (int32_t v : region) {
    const auto it = rings.find(v);
    if (it == rings.end()) continue;
    x[v] = x[v] + (length * std::min(1.0, it->second / ramp)) * field[v];
  }
  clear_field();
  return true;
}

// The vertices of `region` on a thin tube of the mesh (HoleCapOptions::tube_rings): those
// whose `rings`-ring neighbourhood holds fewer than half the 3 k (k + 1) + 1 vertices of a flat
// patch of degree 6, grown by `grow` rings within the region; in the order of `region`. Empty
// when `rings` is 0. `stamp` is scratch kept across calls on disjoint regions: each vertex
// holds the last source whose search reached it (a source is searched from once).
std::vector<int32_t> TubeVertices(const Rows& nb, const std::vector<int32_t>& region, int rings,
                                  int grow, std::vector<int32_t>& stamp) {
  if (rings <= 0) return {};
  if (stamp.empty()) stamp.assign(nb.start.size() - 1, -1);
  const int64_t limit = (3 * int64_t{rings} * (rings + 1) + 1) / 2;
  absl::flat_hash_set<int32_t> tube;
  std::vector<int32_t> frontier, next;
  for (int32_t s : region) {
    // Breadth first, stopped once the neighbourhood holds `limit` vertices: flat enough.
    frontier.assign(1, s);
    stamp[s] = s;
    int64_t count = 1;
    for (int ring = 0; ring < rings && count < limit && !frontier.empty(); ++ring) {
      next.clear();
      for (int32_t v : frontier)
        for (const int32_t* u = nb.begin(v); u != nb.end(v); ++u)
          if (stamp[*u] != s) {
            stamp[*u] = s;
            next.push_back(*u);
            ++count;
          }
      frontier.swap(next);
    }
    if (count < limit) tube.insert(s);
  }
  if (tube.empty()) return {};
  const absl::flat_hash_set<int32_t> in_region(region.begin(), region.end());
  for (int ring = 0; ring < grow; ++ring) {
    std::vector<int32_t> added;
    for (int32_t v : tube)
      for (const int32_t* u = nb.begin(v); u != nb.end(v); ++u)
        if (in_region.contains(*u) && !tube.contains(*u)) added.push_back(*u);
    tube.insert(added.begin(), added.end());
  }
  std::vector<int32_t> out;
  for (int32_t v : region)
    if (tube.contains(v)) out.push_back(v);
  return out;
}

// The mean distance from the held vertices' points (the `pinned` vertices of `region`, at
// `holds`) to the nearest other vertex of the cap at `at`, the held ones aside (they sit on
// their points in the converged plate, and a sweep carries them along): how far a cap passes
// from the points seen inside its gap, in model units. `holds` and `at` run along `region`.
// 0 when none is held.
double HeldPointsDistance(const std::vector<int32_t>& region, const std::vector<char>& pinned,
                          const std::vector<Vec3d>& holds, const std::vector<Vec3d>& at) {
  double sum = 0;
  int count = 0;
  for (size_t i = 0; i < region.size(); ++i) {
    if (!pinned[region[i]]) continue;
    double best = std::numeric_limits<double>::infinity();
    for (size_t j = 0; j < region.size(); ++j)
      if (!pinned[region[j]]) best = std::min(best, SquaredNorm(at[j] - holds[i]));
    if (!std::isfinite(best)) continue;
    sum += std::sqrt(best);
    ++count;
  }
  return count > 0 ? sum / count : 0.0;
}

// Which caps held by points seen inside their gap (`pinned` vertices, at their points in `x`)
// are solved to convergence (HoleCapOptions::converge_held): each such cap is made twice
// without its holds, from the harmonic map and the spline as any cap, once with
// thin_plate_iterations and once converged, and it converges unless that converged plate
// passes farther from the held points, on average, than the other by more than held_margin
// voxels. Caps that wrap converge anyway and are not judged. One entry per region (1:
// converge); the trial's iterations are added to `iterations`. Cancelled when `cancel` fired.
// The solves on `threads` (the same result for any count).
absl::StatusOr<std::vector<char>> HeldCapsToConverge(
    const TriangleMesh& mesh, const Rows& nb, const Rows& star,
    const std::vector<std::vector<int32_t>>& regions, const std::vector<char>& free,
    const std::vector<char>& pinned, const std::vector<Vec3d>& x, double l,
    const HoleCapOptions& options, int64_t& iterations, const CancelToken& cancel,
    int threads) {
  std::vector<char> converges(regions.size(), 0);
  if (!options.converge_held) return converges;
  std::vector<size_t> held;
  std::vector<int32_t> trial;  // the held regions' vertices, holds included
  for (size_t r = 0; r < regions.size(); ++r) {
    if (std::none_of(regions[r].begin(), regions[r].end(),
                     [&](int32_t v) { return pinned[v] != 0; }))
      continue;
    held.push_back(r);
    trial.insert(trial.end(), regions[r].begin(), regions[r].end());
  }
  if (held.empty()) return converges;
  std::sort(trial.begin(), trial.end());
  // The caps from their rims alone: surface-nets positions, the harmonic map, the spline.
  std::vector<Vec3d> kept(mesh.vertices.size());
  for (size_t v = 0; v < kept.size(); ++v) kept[v] = ToVec3d(mesh.vertices[v]);
  const int harmonic_iterations =
      Solve(false, nb, trial, kept, options.harmonic_iterations, options.tolerance * l, cancel,
            threads, options.split_solve_vertices);
  if (harmonic_iterations < 0) return absl::CancelledError("hole caps cancelled");
  iterations += harmonic_iterations;
  std::vector<size_t> judged;
  std::vector<int32_t> judged_vertices;
  for (size_t r : held) {
    if (ShapeCap(mesh, nb, star, regions[r], free, l, options, kept) == CapStart::kWrapped) {
      converges[r] = 1;
      continue;
    }
    judged.push_back(r);
    judged_vertices.insert(judged_vertices.end(), regions[r].begin(), regions[r].end());
  }
  if (judged.empty()) return converges;
  std::sort(judged_vertices.begin(), judged_vertices.end());
  // The converged plate exactly; where the cap is too large for the factor, to `tolerance`
  // only: a bulge stands voxels off.
  std::vector<Vec3d> converged = kept;
  const int kept_iterations =
      Solve(true, nb, judged_vertices, kept, options.thin_plate_iterations, options.tolerance * l,
            cancel, threads, options.split_solve_vertices);
  const int converged_iterations =
      kept_iterations < 0
          ? -1
          : SolveConverged(nb, judged_vertices, converged, options.wrapped_iterations,
                           options.tolerance * l, cancel, threads, options.split_solve_vertices,
                           l, options.coarse_plate_clusters, options.coarse_plate_iterations);
  if (converged_iterations < 0) return absl::CancelledError("hole caps cancelled");
  iterations += kept_iterations + converged_iterations;
  for (size_t r : judged) {
    double kept_sum = 0, converged_sum = 0;
    int count = 0;
    for (int32_t v : regions[r]) {
      if (!pinned[v]) continue;
      kept_sum += Norm(kept[v] - x[v]) / l;
      converged_sum += Norm(converged[v] - x[v]) / l;
      ++count;
    }
    converges[r] = converged_sum <= kept_sum + options.held_margin * count;
  }
  return converges;
}

// The unit normal at v averaged over the vertices within `rings` rings of it: the surface
// nets' faces turn by a voxel's staircase, their sum over a few rings by the surface's shape.
Vec3d RingNormal(const TriangleMesh& mesh, const Rows& nb, const Rows& star, int32_t v,
                 int rings) {
  std::vector<int32_t> seen{v};
  size_t begin = 0;
  for (int ring = 0; ring < rings; ++ring) {
    const size_t end = seen.size();
    for (size_t i = begin; i < end; ++i)
      for (const int32_t* u = nb.begin(seen[i]); u != nb.end(seen[i]); ++u)
        if (std::find(seen.begin(), seen.end(), *u) == seen.end()) seen.push_back(*u);
    begin = end;
  }
  Vec3d sum{0, 0, 0};
  for (int32_t u : seen) sum = sum + Normalized(VertexNormal(mesh, star, u));
  return Normalized(sum);
}

// The crease of a region's cap at a concave corner (HoleCapOptions::corner_angle): the cap's
// gap vertices (the held ones aside) outside two opposite sides of the band (the fixed
// vertices within sample_rings rings, surface-nets positions, read around the band's mean
// normal) move onto the union of the two sides' solids (corner_crease.h), where the
// membrane stayed outside the cap. Returns how many moved.
int64_t CreaseCorner(const TriangleMesh& mesh, const Rows& nb, const Rows& star,
                     const std::vector<int32_t>& region, const std::vector<char>& free,
                     const std::vector<char>& gap, const std::vector<char>& pinned, double l,
                     const HoleCapOptions& options, int threads, std::vector<Vec3d>& x) {
  std::vector<int32_t> cap;
  std::vector<Vec3d> at;
  // The membrane's mean offset outside the cap, along its outward normals. Where it stayed
  // outside, by more than its own offset from the data, the shrink's plates could not
  // enter: a corner narrower than they are. A cap
  // lifted out of a crater the membrane sank into spans a part it had room to enter (a
  // protrusion, a smooth surface), which no crease describes.
  double outside = 0;
  for (int32_t v : region)
    if (gap[v] && !pinned[v]) {
      cap.push_back(v);
      at.push_back((1.0 / l) * x[v]);
      outside += Dot((1.0 / l) * ToVec3d(mesh.vertices[v]) - at.back(),
                     Normalized(VertexNormal(mesh, star, v)));
    }
  if (cap.empty() ||
      !(outside > options.corner_membrane_margin * static_cast<double>(cap.size())))
    return 0;
  const std::vector<int32_t> band = Band(nb, region, free, options.sample_rings);
  std::vector<Vec3d> positions, normals;
  Vec3d axis{0, 0, 0};
  for (int32_t v : band) {
    positions.push_back((1.0 / l) * ToVec3d(mesh.vertices[v]));
    normals.push_back(RingNormal(mesh, nb, star, v, options.corner_normal_rings));
    axis = axis + normals.back();
  }
  if (!(Norm(axis) > 0)) return 0;
  CornerCreaseOptions crease;
  crease.sectors = options.corner_sectors;
  crease.per_sector = options.corner_neighbours;
  crease.min_angle = options.corner_angle;
  crease.flat_tolerance = options.corner_flat_tolerance;
  crease.max_move = options.corner_max_move;
  crease.reach = options.corner_reach;
  const int moved =
      CreaseToCorner(positions, normals, Normalized(axis), crease, absl::MakeSpan(at), threads);
  if (moved == 0) return 0;
  // The moves spread over the cap: where a pair of sides stops qualifying the move jumps to
  // 0, and the faces across the jump fold (the back-off then sends them back toward the
  // membrane). Half of each vertex's move is replaced by its neighbours' mean, the rim's and
  // the held vertices' moves 0.
  absl::flat_hash_map<int32_t, size_t> index;
  for (size_t i = 0; i < cap.size(); ++i) index[cap[i]] = i;
  std::vector<Vec3d> move(cap.size()), next(cap.size());
  for (size_t i = 0; i < cap.size(); ++i) move[i] = at[i] - (1.0 / l) * x[cap[i]];
  for (int step = 0; step < options.corner_smoothing; ++step) {
    for (size_t i = 0; i < cap.size(); ++i) {
      Vec3d sum{0, 0, 0};
      for (const int32_t* u = nb.begin(cap[i]); u != nb.end(cap[i]); ++u)
        if (const auto it = index.find(*u); it != index.end()) sum = sum + move[it->second];
      next[i] = 0.5 * move[i] + (0.5 / std::max(nb.size(cap[i]), 1)) * sum;
    }
    move.swap(next);
  }
  for (size_t i = 0; i < cap.size(); ++i) x[cap[i]] = x[cap[i]] + l * move[i];
  return moved;
}

// The mean of v's neighbours' positions: the umbrella step's target.
Point3f NeighbourMean(const Rows& nb, const TriangleMesh& mesh, int32_t v) {
  Vec3d sum{0, 0, 0};
  for (const int32_t* u = nb.begin(v); u != nb.end(v); ++u)
    sum = sum + ToVec3d(mesh.vertices[*u]);
  return ToPoint3f((1.0 / std::max(nb.size(v), 1)) * sum);
}

// A fold of the caps untangled (HoleCapOptions::untangle_rounds): the cap vertices of the
// crossing pairs (`folded`) and those within `rings` rings of them in the caps take
// `iterations` steps each to their neighbours' mean, together. The faces around each moved
// vertex are marked in `moved_faces` and the vertex in `untangled`. `mark`, all 0, is
// scratch and is left so.
void UntangleFold(const Rows& nb, const Rows& star, const std::vector<char>& in_cap,
                  const std::vector<int32_t>& folded, int rings, int iterations,
                  std::vector<char>& mark, TriangleMesh& mesh, std::vector<char>& moved_faces,
                  std::vector<char>& untangled) {
  std::vector<int32_t> patch;
  for (int32_t v : folded)
    if (in_cap[v] && !mark[v]) {
      mark[v] = 1;
      patch.push_back(v);
    }
  size_t begin = 0;
  for (int ring = 0; ring < rings; ++ring) {
    const size_t end = patch.size();
    for (size_t i = begin; i < end; ++i)
      for (const int32_t* u = nb.begin(patch[i]); u != nb.end(patch[i]); ++u)
        if (in_cap[*u] && !mark[*u]) {
          mark[*u] = 1;
          patch.push_back(*u);
        }
    begin = end;
  }
  std::vector<Point3f> next(patch.size());
  for (int it = 0; it < iterations; ++it) {
    for (size_t i = 0; i < patch.size(); ++i) next[i] = NeighbourMean(nb, mesh, patch[i]);
    for (size_t i = 0; i < patch.size(); ++i) mesh.vertices[patch[i]] = next[i];
  }
  for (int32_t v : patch) {
    mark[v] = 0;
    untangled[v] = 1;
    for (const int32_t* f = star.begin(v); f != star.end(v); ++f) moved_faces[*f] = 1;
  }
}

// The back-off leaves each backed-off vertex where its own crossings let it stop, between its
// cap and its surface-nets place, beside neighbours still on the cap: a ragged crease. Each
// round takes every vertex of `patch` (backed-off vertices) whose neighbours' mean lies farther
// than `min_step` from it one step to that mean, then sends back to where the round found it
// every vertex of a crossing pair that the round moved, until the search (on `threads`) finds
// none: the mesh stays as embedded as the back-off left it. The vertices that stop moving stop
// costing a search. Returns how many vertices ended away from where the back-off left them.
int64_t SettleBackedOff(const Rows& nb, const Rows& star, const std::vector<int32_t>& patch,
                        int rounds, double min_step, int threads, TriangleMesh& mesh,
                        FaceBlockBoxes& blocks) {
  if (rounds == 0 || patch.empty()) return 0;
  std::vector<int32_t> slot(mesh.vertices.size(), -1);
  std::vector<Point3f> start(patch.size()), prev(patch.size()), next(patch.size());
  for (size_t i = 0; i < patch.size(); ++i) {
    slot[patch[i]] = static_cast<int32_t>(i);
    start[i] = mesh.vertices[patch[i]];
  }
  std::vector<char> dirty(mesh.faces.size(), 0);
  for (int round = 0; round < rounds; ++round) {
    for (size_t i = 0; i < patch.size(); ++i) {
      prev[i] = mesh.vertices[patch[i]];
      next[i] = NeighbourMean(nb, mesh, patch[i]);
    }
    std::fill(dirty.begin(), dirty.end(), 0);
    bool any = false;
    for (size_t i = 0; i < patch.size(); ++i) {
      if (SquaredNorm(ToVec3d(next[i]) - ToVec3d(prev[i])) <= min_step * min_step) continue;
      any = true;
      mesh.vertices[patch[i]] = next[i];
      for (const int32_t* f = star.begin(patch[i]); f != star.end(patch[i]); ++f) dirty[*f] = 1;
    }
    if (!any) break;
    // `dirty` marks every face whose vertices moved since the last search, as `blocks` needs.
    for (;;) {
      std::vector<int32_t> back;
      for (const auto& [a, b] : FindIntersectingFacesNear(mesh, dirty, threads, &blocks))
        for (int32_t f : {a, b})
          for (int32_t v : mesh.faces[f])
            if (slot[v] >= 0 && mesh.vertices[v] != prev[slot[v]]) back.push_back(v);
      if (back.empty()) break;
      std::fill(dirty.begin(), dirty.end(), 0);
      for (int32_t v : back) {
        mesh.vertices[v] = prev[slot[v]];
        for (const int32_t* f = star.begin(v); f != star.end(v); ++f) dirty[*f] = 1;
      }
    }
  }
  int64_t moved = 0;
  for (size_t i = 0; i < patch.size(); ++i) moved += mesh.vertices[patch[i]] != start[i];
  return moved;
}

absl::Status Validate(double voxel_size, const HoleCapOptions& o) {
  if (!(voxel_size > 0) || !std::isfinite(voxel_size))
    return absl::InvalidArgumentError(absl::StrCat("voxel size ", voxel_size, " is not positive"));
  if (!(o.gap_radius > 0) || o.min_gap_vertices < 1 || o.rim_rings < 0 ||
      o.harmonic_iterations < 0 || !(o.tolerance > 0) || o.sample_rings < 1 ||
      o.max_samples < 3 || !(o.smoothing >= 0) || !(o.min_rim_cosine >= -1) ||
      !(o.wrap_rms >= 0) || o.wrapped_iterations < 0 || !(o.tube_flatness >= 0) ||
      !(o.tube_lead >= 0) || o.tube_rings < 0 || o.tube_rings > 64 ||
      !(o.swept_length >= 0 && o.swept_length <= 16) ||
      !(o.spline_swept_length >= 0 && o.spline_swept_length <= 16) ||
      !(o.sphere_band_fit >= 0) ||
      !(o.sphere_margin >= 0) || !(o.converged_tolerance > 0) ||
      o.back_off_halvings < 0 || o.settle_rounds < 0 || o.settle_rounds > 1000 ||
      !(o.settle_min_step >= 0 && o.settle_min_step <= 1) ||
      !(o.max_shell_share > 0 && o.max_shell_share <= 1) ||
      o.min_median_points < 1 || o.min_median_points > 1000 ||
      !(o.anchor_radius > 0 && o.anchor_radius <= 64) || !(o.held_margin >= 0) ||
      !(o.corner_angle >= 0) || o.corner_sectors < 2 || o.corner_sectors > 360 ||
      o.corner_neighbours < 1 || o.corner_neighbours > 64 || !(o.corner_flat_tolerance >= 0) ||
      !(o.corner_max_move >= 0) || !(o.corner_reach > 0) || !(o.corner_reach <= 1e6) ||
      !(o.corner_membrane_margin >= 0) ||
      o.corner_smoothing < 0 || o.corner_smoothing > 100 ||
      o.corner_normal_rings < 0 || o.corner_normal_rings > 8 || o.untangle_rounds < 0 ||
      o.untangle_rounds > 1000 || o.untangle_rings < 0 || o.untangle_rings > 16 ||
      o.untangle_iterations < 1 || o.untangle_iterations > 100 || o.split_solve_vertices < 1 ||
      o.coarse_plate_vertices < 1 || o.coarse_plate_clusters < 1 ||
      o.coarse_plate_clusters > (int64_t{1} << 24) || o.coarse_plate_iterations < 0)
    return absl::InvalidArgumentError(absl::StrCat(
        "hole cap options out of range: gap_radius ", o.gap_radius, ", min_gap_vertices ",
        o.min_gap_vertices, ", rim_rings ", o.rim_rings, ", harmonic_iterations ",
        o.harmonic_iterations, ", tolerance ", o.tolerance, ", sample_rings ", o.sample_rings,
        ", max_samples ", o.max_samples, ", smoothing ", o.smoothing, ", min_rim_cosine ",
        o.min_rim_cosine, ", wrap_rms ", o.wrap_rms, ", wrapped_iterations ",
        o.wrapped_iterations, ", tube_flatness ", o.tube_flatness, ", tube_lead ", o.tube_lead,
        ", tube_rings ", o.tube_rings,
        ", swept_length ", o.swept_length, ", spline_swept_length ", o.spline_swept_length,
        ", sphere_band_fit ", o.sphere_band_fit,
        ", sphere_margin ", o.sphere_margin, ", converged_tolerance ", o.converged_tolerance,
        ", back_off_halvings ", o.back_off_halvings, ", settle_rounds ", o.settle_rounds,
        ", settle_min_step ", o.settle_min_step, ", split_solve_vertices ",
        o.split_solve_vertices,
        ", max_shell_share ", o.max_shell_share,
        ", min_median_points ", o.min_median_points, ", anchor_radius ", o.anchor_radius,
        ", held_margin ", o.held_margin, ", corner_angle ", o.corner_angle, ", corner_sectors ",
        o.corner_sectors, ", corner_neighbours ", o.corner_neighbours,
        ", corner_flat_tolerance ", o.corner_flat_tolerance, ", corner_max_move ",
        o.corner_max_move, ", corner_reach ", o.corner_reach, ", corner_membrane_margin ",
        o.corner_membrane_margin,
        ", corner_smoothing ", o.corner_smoothing,
        ", corner_normal_rings ", o.corner_normal_rings, ", untangle_rounds ",
        o.untangle_rounds, ", untangle_rings ", o.untangle_rings, ", untangle_iterations ",
        o.untangle_iterations, ", coarse_plate_vertices ", o.coarse_plate_vertices,
        ", coarse_plate_clusters ", o.coarse_plate_clusters, ", coarse_plate_iterations ",
        o.coarse_plate_iterations));
  return absl::OkStatus();
}

// The connected components of the marked vertices, in order of their lowest vertex.
std::vector<std::vector<int32_t>> Components(const Rows& nb, const std::vector<char>& marked) {
  const int32_t nv = static_cast<int32_t>(marked.size());
  std::vector<char> seen(nv, 0);
  std::vector<std::vector<int32_t>> components;
  for (int32_t s = 0; s < nv; ++s) {
    if (!marked[s] || seen[s]) continue;
    std::vector<int32_t> c{s};
    seen[s] = 1;
    for (size_t i = 0; i < c.size(); ++i)
      for (const int32_t* u = nb.begin(c[i]); u != nb.end(c[i]); ++u)
        if (marked[*u] && !seen[*u]) {
          seen[*u] = 1;
          c.push_back(*u);
        }
    components.push_back(std::move(c));
  }
  return components;
}

}  // namespace

absl::Status CapHoles(TriangleMesh& mesh, double voxel_size, absl::Span<const Point3f> points,
                      const HoleCapOptions& options, HoleCapStats* stats,
                      const CancelToken& cancel, int threads,
                      const PointRowGrid* points_grid) {
  if (absl::Status s = Validate(voxel_size, options); !s.ok()) return s;
  HoleCapStats local;
  HoleCapStats& st = stats ? *stats : local;
  st = HoleCapStats{};
  const int32_t nv = static_cast<int32_t>(mesh.vertices.size());
  if (!options.enabled || nv == 0 || points.empty()) return absl::OkStatus();
  const double l = voxel_size;

  // One index of the points, cells of the gap radius: the gap search's, and the back-off's
  // settling asks it which backed-off vertices hold points.
  std::optional<PointRowGrid> own_grid;
  if (points_grid == nullptr) own_grid.emplace(points, options.gap_radius * l, threads);
  const PointRowGrid& grid = points_grid != nullptr ? *points_grid : *own_grid;
  // Gap vertices: no input point within gap_radius. The other vertices' counts of points
  // within gap_radius, in a histogram (the last bin holds every larger count), for their median.
  // The points with no vertex within gap_radius: buried in the solid or left outside it.
  absl::StatusOr<GapVertices> found =
      FindGapVertices(mesh, points, options.gap_radius * l, options.min_median_points,
                      options.anchor_remote_points, options.min_gap_vertices, threads, cancel,
                      &grid);
  if (!found.ok()) return found.status();
  const std::vector<char>& gap = found->gap;
  const int64_t count = found->count;
  if (count < options.min_gap_vertices) return absl::OkStatus();
  // Below the median: more than half of the vertices on the data have fewer points near.
  int64_t fewer = 0;
  for (int k = 0; k < options.min_median_points; ++k) fewer += found->histogram[k];
  const bool sparse = 2 * fewer > nv - count;
  const std::vector<Point3f> remote = std::move(found->remote);
  if (cancel.cancelled()) return absl::CancelledError("hole caps cancelled");
  Rows nb, star;
  BuildRows(mesh, nb, star);

  // Regions: gaps large enough, grown by rim_rings rings; each needs a fixed neighbour.
  std::vector<char> free(nv, 0);
  for (const auto& c : Components(nb, gap))
    if (static_cast<int64_t>(c.size()) >= options.min_gap_vertices)
      for (int32_t v : c) free[v] = 1;
  for (int ring = 0; ring < options.rim_rings; ++ring) {
    std::vector<char> grown = free;
    for (int32_t v = 0; v < nv; ++v)
      if (free[v])
        for (const int32_t* u = nb.begin(v); u != nb.end(v); ++u) grown[*u] = 1;
    free.swap(grown);
  }
  // Each vertex's shell and the shells' sizes, for the share of a region in its shell.
  std::vector<int32_t> shell(nv, -1);
  std::vector<int64_t> shell_size;
  for (int32_t s = 0; s < nv; ++s) {
    if (shell[s] >= 0) continue;
    const int32_t id = static_cast<int32_t>(shell_size.size());
    std::vector<int32_t> stack{s};
    shell[s] = id;
    int64_t size = 0;
    while (!stack.empty()) {
      const int32_t v = stack.back();
      stack.pop_back();
      ++size;
      for (const int32_t* u = nb.begin(v); u != nb.end(v); ++u)
        if (shell[*u] < 0) {
          shell[*u] = id;
          stack.push_back(*u);
        }
    }
    shell_size.push_back(size);
  }
  std::vector<std::vector<int32_t>> regions;
  for (auto& c : Components(nb, free)) {
    bool held = false;
    for (int32_t v : c)
      for (const int32_t* u = nb.begin(v); u != nb.end(v) && !held; ++u) held = !free[*u];
    const double share =
        static_cast<double>(c.size()) / static_cast<double>(shell_size[shell[c[0]]]);
    if (held && share <= options.max_shell_share && !sparse) {
      regions.push_back(std::move(c));
    } else {
      ++st.uncapped_regions;
      for (int32_t v : c) free[v] = 0;
    }
  }
  if (regions.empty()) return absl::OkStatus();
  std::vector<int32_t> free_list;
  for (const auto& c : regions) free_list.insert(free_list.end(), c.begin(), c.end());
  std::sort(free_list.begin(), free_list.end());

  std::vector<Vec3d> x(nv);
  for (int32_t v = 0; v < nv; ++v) x[v] = ToVec3d(mesh.vertices[v]);
  // Anchors: a remote point whose nearest vertex (within anchor_radius) is a cap vertex holds
  // that vertex at the mean of such points; the cap is solved around it. Every vertex is a
  // candidate: a point nearest to the data around a gap is no cap's.
  std::vector<char> pinned(nv, 0);
  if (!remote.empty()) {
    const double reach = options.anchor_radius * l;
    const PointRowGrid grid(remote, reach);
    std::vector<double> best(grid.num_points(), reach * reach);
    std::vector<int32_t> owner(grid.num_points(), -1);
    const float* px = grid.xs();
    const float* py = grid.ys();
    const float* pz = grid.zs();
    for (int32_t v = 0; v < nv; ++v) {
      if (v % kCancelPollVertices == 0 && cancel.cancelled())
        return absl::CancelledError("hole caps cancelled");
      const Vec3d c = x[v];
      grid.ForEachRun(c, reach, [&](uint32_t begin, uint32_t end) {
        for (uint32_t i = begin; i < end; ++i) {
          const double dx = px[i] - c[0], dy = py[i] - c[1], dz = pz[i] - c[2];
          const double d2 = dx * dx + dy * dy + dz * dz;
          if (d2 < best[i]) {
            best[i] = d2;
            owner[i] = v;
          }
        }
      });
    }
    std::vector<Vec3d> sum(nv, Vec3d{0, 0, 0});
    std::vector<int32_t> held(nv, 0);
    for (size_t i = 0; i < grid.num_points(); ++i)
      if (owner[i] >= 0 && free[owner[i]]) {
        sum[owner[i]] = sum[owner[i]] + Vec3d{px[i], py[i], pz[i]};
        ++held[owner[i]];
      }
    for (int32_t v : free_list)
      if (held[v] > 0) {
        pinned[v] = 1;
        x[v] = (1.0 / held[v]) * sum[v];
        ++st.anchors;
      }
  }
  std::vector<char> held_converges;
  int64_t trial_iterations = 0;
  if (absl::StatusOr<std::vector<char>> judged =
          HeldCapsToConverge(mesh, nb, star, regions, free, pinned, x, l, options,
                             trial_iterations, cancel, threads);
      judged.ok())
    held_converges = *std::move(judged);
  else
    return judged.status();
  std::vector<int32_t> solve_list;
  for (int32_t v : free_list)
    if (!pinned[v]) solve_list.push_back(v);
  const int it = Solve(false, nb, solve_list, x, options.harmonic_iterations, options.tolerance * l,
                       cancel, threads, options.split_solve_vertices);
  if (it < 0) return absl::CancelledError("hole caps cancelled");
  st.iterations = it + trial_iterations;
  // The caps' vertices by their thin plate's iterations: the caps solved to convergence
  // apart, one list each (see below).
  std::vector<int32_t> blended;
  std::vector<std::vector<int32_t>> converging;
  std::vector<int32_t> stamp;  // TubeVertices' scratch
  // Spline caps whose band has a sphere: their converged plate is solved apart, to be compared.
  std::vector<std::optional<AlgebraicSphere>> spheres(regions.size());
  std::vector<int32_t> candidates;
  std::vector<CapStart> starts(regions.size(), CapStart::kSpline);
  for (size_t r = 0; r < regions.size(); ++r) {
    // The region's vertices but the held ones.
    std::vector<int32_t> region;
    for (int32_t v : regions[r])
      if (!pinned[v]) region.push_back(v);
    // Where the spline cannot shape it, the thin plate starts from the harmonic map.
    const CapStart start = ShapeCap(mesh, nb, star, region, free, l, options, x);
    starts[r] = start;
    if (start != CapStart::kSpline) ++st.harmonic_starts;
    if (start == CapStart::kWrapped) ++st.wrapped;
    // A held cap converges (HeldCapsToConverge), whatever its start.
    const bool converges = start == CapStart::kWrapped || held_converges[r];
    if (held_converges[r] && start != CapStart::kWrapped) ++st.held_converged;
    if (converges) {
      // A wrapped cap's thin tube is its own system, solved after the rest (tube_rings); a
      // tube that is the whole cap is no part apart.
      std::vector<int32_t> tube;
      if (start == CapStart::kWrapped)
        tube = TubeVertices(nb, region, options.tube_rings, options.rim_rings, stamp);
      if (tube.size() >= region.size()) tube.clear();
      if (!tube.empty()) {
        const absl::flat_hash_set<int32_t> in_tube(tube.begin(), tube.end());
        std::erase_if(region, [&](int32_t v) { return in_tube.contains(v); });
        st.tube_vertices += static_cast<int64_t>(tube.size());
      }
      converging.push_back(region);
      if (!tube.empty()) converging.push_back(std::move(tube));
    } else {
      blended.insert(blended.end(), region.begin(), region.end());
    }
    ++st.regions;
    if (!converges && start == CapStart::kSpline &&
        options.thin_plate_iterations < options.wrapped_iterations)
      spheres[r] = BandSphere(mesh, nb, star, region, free, l, options);
    if (spheres[r]) candidates.insert(candidates.end(), region.begin(), region.end());
  }
  st.vertices = static_cast<int64_t>(free_list.size());
  std::vector<Vec3d> converged;
  if (!candidates.empty()) {
    std::sort(candidates.begin(), candidates.end());
    converged = x;
    const int ci =
        Solve(true, nb, candidates, converged, options.wrapped_iterations,
              options.converged_tolerance * l, cancel, threads, options.split_solve_vertices);
    if (ci < 0) return absl::CancelledError("hole caps cancelled");
    st.iterations += ci;
  }
  if (options.thin_plate_iterations > 0 && !blended.empty()) {
    std::sort(blended.begin(), blended.end());
    const int bi = Solve(true, nb, blended, x, options.thin_plate_iterations, options.tolerance * l,
                         cancel, threads, options.split_solve_vertices);
    if (bi < 0) return absl::CancelledError("hole caps cancelled");
    st.iterations += bi;
  }
  // Each cap that converges is solved on its own: one system's steps and stopping test
  // belong to one plate, so a small cap stops once its own steps fall below the tolerance
  // instead of running on as long as the largest cap of the mesh, and a cap that reaches
  // wrapped_iterations does so at its own size.
  for (std::vector<int32_t>& region : converging) {
    if (options.wrapped_iterations == 0) break;
    std::sort(region.begin(), region.end());
    // Past the factor's size, from the coarse plate (HoleCapOptions::coarse_plate_iterations).
    const bool coarse =
        static_cast<int64_t>(region.size()) > options.coarse_plate_vertices &&
        CoarsePlateStart(nb, region, l, options.coarse_plate_clusters, x);
    const int ci = Solve(true, nb, region, x,
                         coarse ? std::min(options.wrapped_iterations,
                                           options.coarse_plate_iterations)
                                : options.wrapped_iterations,
                         options.converged_tolerance * l, cancel, threads,
                         options.split_solve_vertices);
    if (ci < 0) return absl::CancelledError("hole caps cancelled");
    st.iterations += ci;
  }
  // The band's sphere picks between the two plates: the mean distance of the cap's gap
  // vertices from it (the rim's rings, near the data, are the fit's to settle).
  for (size_t r = 0; r < regions.size(); ++r) {
    if (!spheres[r]) continue;
    double kept = 0, solved = 0;
    int count = 0;
    for (int32_t v : regions[r]) {
      if (!gap[v]) continue;
      kept += spheres[r]->Distance((1.0 / l) * x[v]);
      solved += spheres[r]->Distance((1.0 / l) * converged[v]);
      ++count;
    }
    if (count == 0 || !(solved < kept - options.sphere_margin * count)) continue;
    for (int32_t v : regions[r]) x[v] = converged[v];
    ++st.sphere_converged;
  }
  // Posts whose end the hole swallowed run on past the rim (HoleCapOptions::swept_length,
  // spline_swept_length), held caps where their points agree. A rim in its plane (the
  // harmonic start: an open flat base) is no post.
  std::vector<Vec3d> sweep_field;  // SweepCap's scratch, made for the first swept cap
  for (size_t r = 0; r < regions.size(); ++r) {
    const double length = starts[r] == CapStart::kWrapped  ? options.swept_length
                          : starts[r] == CapStart::kSpline ? options.spline_swept_length
                                                           : 0.0;
    if (!(length > 0)) continue;
    const std::optional<Tube> tube =
        FindTube(mesh, nb, star, regions[r], free, gap, x, l, options);
    if (!tube) continue;
    const bool held =
        std::any_of(regions[r].begin(), regions[r].end(), [&](int32_t v) { return pinned[v]; });
    // A held cap's positions before the sweep (SweepCap moves only the region's vertices),
    // put back when the swept cap passes farther from its points.
    std::vector<Vec3d> unswept;
    if (held)
      for (int32_t v : regions[r]) unswept.push_back(x[v]);
    // A spline cap's rim is a height field around the post: its walls run along the axis. A
    // wrapped rim's walls turn with it (a thin part's edge, a post cut aslant), each toward
    // the middle of the cap.
    const std::optional<Vec3d> along =
        starts[r] == CapStart::kSpline ? std::optional<Vec3d>(tube->axis) : std::nullopt;
    if (sweep_field.empty()) sweep_field.assign(x.size(), Vec3d{0, 0, 0});
    if (!SweepCap(mesh, nb, star, regions[r], free, gap, length * tube->radius * l, along,
                  options, x, sweep_field, cancel))
      return absl::CancelledError("hole caps cancelled");
    if (held) {
      std::vector<Vec3d> swept;
      for (int32_t v : regions[r]) swept.push_back(x[v]);
      if (HeldPointsDistance(regions[r], pinned, unswept, swept) / l >
          HeldPointsDistance(regions[r], pinned, unswept, unswept) / l + options.held_margin) {
        for (size_t i = 0; i < regions[r].size(); ++i) x[regions[r][i]] = unswept[i];
        continue;
      }
    }
    ++st.swept;
  }

  // Concave corners: a band of two surfaces carries each into the hole until they meet.
  if (options.corner_angle <= 180)
    for (size_t r = 0; r < regions.size(); ++r) {
      if (cancel.cancelled()) return absl::CancelledError("hole caps cancelled");
      const int64_t moved = CreaseCorner(mesh, nb, star, regions[r], free, gap, pinned, l,
                                         options, threads, x);
      if (moved > 0) {
        ++st.creased;
        st.creased_vertices += moved;
      }
    }

  // Write the caps, then take back the parts that cross the mesh.
  const std::vector<Point3f> before = mesh.vertices;
  std::vector<char> dirty(mesh.faces.size(), 0);
  for (int32_t v : free_list) {
    mesh.vertices[v] = ToPoint3f(x[v]);
    st.max_lift = std::max(st.max_lift, Norm(x[v] - ToVec3d(before[v])) / l);
    for (const int32_t* f = star.begin(v); f != star.end(v); ++f) dirty[*f] = 1;
  }
  // The runs' boxes, kept from round to round: a round reads only the faces of the runs
  // near the faces that moved (`dirty` marks every face whose vertices moved since the last).
  FaceBlockBoxes blocks;
  // Folds first: a pair whose two faces each hold a moved cap vertex is the caps' own
  // layout, untangled in place (UntangleFold); a region whose folds outlast untangle_rounds
  // goes back to its cap as solved, for the back-off below, as every other crossing.
  if (options.untangle_rounds > 0) {
    std::vector<int32_t> region_of(nv, -1);
    for (size_t r = 0; r < regions.size(); ++r)
      for (int32_t v : regions[r]) region_of[v] = static_cast<int32_t>(r);
    std::vector<char> in_cap(nv, 0), mark(nv, 0), untangled(nv, 0);
    for (int32_t v : free_list) in_cap[v] = 1;
    auto capped = [&](int32_t f) {
      for (int32_t v : mesh.faces[f])
        if (in_cap[v] && mesh.vertices[v] != before[v]) return true;
      return false;
    };
    std::vector<char> moved_faces = dirty, failed(regions.size(), 0);
    for (int round = 0;; ++round) {
      std::vector<int32_t> folded;
      for (const auto& [a, b] : FindIntersectingFacesNear(mesh, moved_faces, threads, &blocks))
        if (capped(a) && capped(b))
          for (int32_t f : {a, b})
            for (int32_t v : mesh.faces[f])
              if (in_cap[v] && mesh.vertices[v] != before[v]) folded.push_back(v);
      if (folded.empty()) break;
      if (round == options.untangle_rounds) {
        for (int32_t v : folded)
          if (region_of[v] >= 0) failed[region_of[v]] = 1;
        break;
      }
      std::fill(moved_faces.begin(), moved_faces.end(), 0);
      UntangleFold(nb, star, in_cap, folded, options.untangle_rings,
                   options.untangle_iterations, mark, mesh, moved_faces, untangled);
    }
    // `dirty` still marks every face around a cap vertex: the back-off's first search reads
    // them all, untangled or put back.
    for (int32_t v : free_list) {
      if (region_of[v] >= 0 && failed[region_of[v]])
        mesh.vertices[v] = ToPoint3f(x[v]);
      else
        st.untangled += untangled[v];
    }
  }
  std::vector<int> level(nv, 0);
  std::vector<char> backed(nv, 0);
  // Not cancelled: the caps are written, and only this loop makes them an embedded mesh.
  for (;;) {
    const std::vector<std::pair<int32_t, int32_t>> pairs =
        FindIntersectingFacesNear(mesh, dirty, threads, &blocks);
    std::vector<int32_t> moved;
    for (const auto& [a, b] : pairs)
      for (int32_t f : {a, b})
        for (int32_t v : mesh.faces[f])
          if (mesh.vertices[v] != before[v]) moved.push_back(v);
    if (moved.empty()) break;  // none, or only crossings of the input
    std::sort(moved.begin(), moved.end());
    moved.erase(std::unique(moved.begin(), moved.end()), moved.end());
    std::fill(dirty.begin(), dirty.end(), 0);
    for (int32_t v : moved) {
      const Vec3d home = ToVec3d(before[v]);
      mesh.vertices[v] = ++level[v] > options.back_off_halvings
                             ? before[v]
                             : ToPoint3f(home + 0.5 * (ToVec3d(mesh.vertices[v]) - home));
      if (!backed[v]) ++st.backed_off;
      backed[v] = 1;
      for (const int32_t* f = star.begin(v); f != star.end(v); ++f) dirty[*f] = 1;
    }
  }
  // A backed-off vertex with points near where it stopped holds the surface to them (the fit
  // starts from it): it stays.
  std::vector<int32_t> settling;
  const double near = options.gap_radius * l;
  for (int32_t v : free_list) {
    if (!backed[v]) continue;
    bool held = false;
    grid.ForEachRun(ToVec3d(mesh.vertices[v]), near, [&](uint32_t begin, uint32_t end) {
      for (uint32_t i = begin; i < end && !held; ++i) {
        const Vec3d d = Vec3d{grid.xs()[i], grid.ys()[i], grid.zs()[i]} - ToVec3d(mesh.vertices[v]);
        held = SquaredNorm(d) <= near * near;
      }
    });
    if (!held) settling.push_back(v);
  }
  st.settled = SettleBackedOff(nb, star, settling, options.settle_rounds,
                               options.settle_min_step * l, threads, mesh, blocks);
  return absl::OkStatus();
}

}  // namespace membrane

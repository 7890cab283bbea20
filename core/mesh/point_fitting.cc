#include "core/mesh/point_fitting.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "core/base/parallel_tasks.h"
#include "core/engine/arena_allocator.h"
#include "core/geometry/vec3.h"
#include "core/mesh/crease_fit.h"
#include "core/mesh/fan_embedding.h"
#include "core/mesh/near_point_sums.h"
#include "core/mesh/plane_fit.h"
#include "core/mesh/point_cell_means.h"
#include "core/mesh/point_row_grid.h"
#include "core/mesh/self_intersection.h"
#include "core/mesh/triangle_intersection.h"
#include "core/mesh/vertex_stars.h"

namespace membrane {
namespace {

// Fractions of the way to the target tried in turn (recipe 3 step 5); a move that makes two
// triangles cross goes back through the same fractions, then to where it started.
constexpr double kStepFractions[] = {1.0, 0.5, 0.25};
constexpr int kFullyBackedOff = 3;
constexpr int kRepairHalvings = 6;
constexpr int kCancelPollVertices = 4096;
// The share of the fit's progress that its rounds count; the final search is the rest.
constexpr double kRoundsShare = 0.85;
// Slab thickness in voxels. A face's vertices lie in neighbouring surface-nets cells, so their
// input positions are less than 2 voxels apart along any axis: with slabs of 4, a vertex's ring
// lies in its own slab or the next ones (checked, not assumed).
constexpr double kSlabVoxels = 4;
// The set-up's passes over vertices and faces run on ranges on the threads from this many items.
constexpr int64_t kMinRangeItems = int64_t{1} << 16;

// The fit's per-vertex and per-face arrays: left unset when made, written first on the
// set-up's ranges.
template <typename T>
using Unfilled = std::vector<T, UnfilledAllocator<T>>;

// The fit's indexes: the faces around each vertex, the mesh's vertex rings (walked from those
// stars) and the points' grid, each built on the run's threads.
struct FitIndexes {
  VertexStars stars;
  MeshFans fans;
  PointRowGrid points;
};

FitIndexes BuildIndexes(const TriangleMesh& mesh, double voxel_size,
                        absl::Span<const Point3f> points, const FitOptions& options,
                        std::optional<PointRowGrid> points_grid) {
  // A dense cloud's means come from an index of every point (the caller's when given, else
  // built on the run's threads), before the two indexes that then read the few means.
  std::optional<PointCellMeans> merged;
  if (static_cast<double>(points.size()) >=
      options.dense_points_per_vertex * static_cast<double>(mesh.vertices.size())) {
    if (!points_grid) points_grid.emplace(points, options.search_radius * voxel_size,
                                          options.threads);
    merged.emplace(MeanPerSubCell(*points_grid, options.mean_split));
  }
  points_grid.reset();
  const int threads = options.threads;
  VertexStars stars =
      FacesAroundVertices(mesh.faces, static_cast<int32_t>(mesh.vertices.size()), threads);
  MeshFans fans(mesh.faces, stars, threads);
  // Cells of half the search radius: a query reads 5x5 rows of 5 cells, a box little larger
  // than its ball.
  const double cell = 0.5 * options.search_radius * voxel_size;
  return FitIndexes{std::move(stars), std::move(fans),
                    merged ? PointRowGrid(merged->means, cell, threads, PointRowGrid::Limits(),
                                          merged->counts)
                           : PointRowGrid(points, cell, threads)};
}

class Fitter {
 public:
  Fitter(TriangleMesh& mesh, double voxel_size, FitIndexes indexes, const FitOptions& options,
         const std::vector<Point3f>* fallback)
      : mesh_(mesh),
        l_(voxel_size),
        options_(options),
        fallback_(fallback),
        grid_(options.output_grid),
        fans_(std::move(indexes.fans)),
        points_(std::move(indexes.points)) {
    const int32_t nv = static_cast<int32_t>(mesh.vertices.size());
    const int32_t nf = static_cast<int32_t>(mesh.faces.size());
    star_start_ = std::move(indexes.stars.start);
    star_ = std::move(indexes.stars.faces);
    // The per-item passes below on ranges on the threads, each range writing its own items
    // first (their page faults with them).
    rest_normal_.resize(nf);
    ForRanges(nf, [&](int64_t f) {
      const Triangle3d t = Tri(static_cast<int32_t>(f));
      rest_normal_[f] = TriangleNormal(t[0], t[1], t[2]);
    });
    // Snapped after the input normals are taken: a face the grid flattens or flips is then
    // refused by FaceOk like any other, and its vertices can only move out of it.
    if (fallback_ != nullptr) repair_level_.resize(nv);
    changed_at_.resize(nv);
    settled_at_.resize(nv);
    level_.resize(nv);
    in_round_.resize(nv);
    backed_off_.resize(nv);
    start_.resize(nv);
    target_.resize(nv);
    rest_.resize(nv);
    ForRanges(nv, [&](int64_t v) {
      Point3f& p = mesh.vertices[v];
      rest_[v] = p;
      p = grid_.Snap(p);
      if (fallback_ != nullptr) repair_level_[v] = 0;
      changed_at_[v] = 0;
      settled_at_[v] = -1;
      level_[v] = 0;
      in_round_[v] = 0;
      backed_off_[v] = 0;
      start_[v] = Point3f{};
      target_[v] = Vec3d{};
    });
    // "Non-zero area": twice the area above a tiny fraction of a voxel face, so that no later
    // float32 rounding can flip a sliver.
    min_double_area_ = 1e-6 * l_ * l_;
    dirty_.assign(nf, 0);
    AssignSlabs();
  }

  int64_t weighed_points() const { return static_cast<int64_t>(points_.num_points()); }

  // `progress`: the rounds count the vertices of the slabs as they are fitted (rounds times
  // every vertex) up to 85% of it, the final search the rest.
  absl::Status Run(const CancelToken& cancel, ProgressRange progress, FitStats& stats) {
    const ProgressRange rounds = progress.Part(0, kRoundsShare);
    rounds.Begin(static_cast<int64_t>(options_.rounds) * static_cast<int64_t>(rest_.size()));
    for (int round = 0; round < options_.rounds; ++round)
      for (int parity = 0; parity < 2; ++parity)
        if (!RunPhase(round, parity, cancel, rounds, stats)) {
          // Leave a valid mesh: nothing is verified before the end, so undo every move.
          for (int32_t u : moved_) Set(u, start_[u], clock_);
          return absl::CancelledError("fitting cancelled");
        }
    // With a fallback or after snapping the input is not known to be clean: the first search
    // covers it all.
    Verify(/*search_all=*/fallback_ != nullptr || !grid_.lossless(), stats);
    progress.Part(kRoundsShare, 1).Done();
    return absl::OkStatus();
  }

 private:
  Vec3d Pos(int32_t v) const { return ToVec3d(mesh_.vertices[v]); }
  // The written position nearest `x`: float32, on the output grid.
  Point3f Place(const Vec3d& x) const { return grid_.Snap(ToPoint3f(x)); }
  Triangle3d Tri(int32_t f) const {
    const auto& t = mesh_.faces[f];
    return {Pos(t[0]), Pos(t[1]), Pos(t[2])};
  }
  // `clock` is the move clock of the slab being fitted, or clock_ outside the rounds.
  void Set(int32_t v, const Point3f& p, int64_t& clock) {
    mesh_.vertices[v] = p;
    changed_at_[v] = ++clock;
  }

  // What fitting one slab in one phase writes besides the slab's own vertices: every slab of a
  // phase has its own, so that slabs can be fitted side by side.
  struct SlabWork {
    int64_t clock = 0;
    FitStats stats;
    std::vector<int32_t> moved;
    std::vector<Vec3d> ring_pos;       // scratch of FanEmbeddedAt
    std::vector<Triangle3d> new_tri;  // scratch of StarOk
    std::vector<FramePoint> near;     // scratch of CurvedTarget's crease try
  };

  // The set-up's ranges of n items: 4 a thread with threads > 1 and kMinRangeItems items or
  // more, else one.
  int64_t NumRanges(int64_t n) const {
    const int threads = options_.threads;
    return threads > 1 && n >= kMinRangeItems ? 4 * int64_t{threads} : 1;
  }
  // Calls range(r, begin, end) for the NumRanges(n) ranges of [0, n) on the threads.
  template <typename Range>
  void ForEachRange(int64_t n, Range range) const {
    const int64_t ranges = NumRanges(n);
    RunTasks(options_.threads, ranges,
             [&](int, int64_t r) { range(r, r * n / ranges, (r + 1) * n / ranges); });
  }
  // Calls item(i) for every i in [0, n), each from one range.
  template <typename Item>
  void ForRanges(int64_t n, Item item) const {
    ForEachRange(n, [&](int64_t, int64_t begin, int64_t end) {
      for (int64_t i = begin; i < end; ++i) item(i);
    });
  }

  // Slabs across the longest axis of the input, by input position, each listing its vertices in
  // index order. The rounds fit the even slabs, then the odd ones: two slabs of one parity are
  // never neighbours, and every read and write of fitting a vertex stays within its ring, so
  // the slabs of a phase are independent and the result is the same for any thread count.
  // Should a face span more than two slabs (never seen), everything is one slab.
  // The vertices are counted and placed per range of vertices on the threads, in the one-range
  // order.
  void AssignSlabs() {
    const int32_t nv = static_cast<int32_t>(rest_.size());
    const int64_t nf = static_cast<int64_t>(mesh_.faces.size());
    const int64_t ranges = NumRanges(nv);
    std::vector<std::array<float, 3>> range_lo(static_cast<size_t>(ranges), rest_[0]);
    std::vector<std::array<float, 3>> range_hi(static_cast<size_t>(ranges), rest_[0]);
    ForEachRange(nv, [&](int64_t r, int64_t begin, int64_t end) {
      std::array<float, 3>& lo = range_lo[r];
      std::array<float, 3>& hi = range_hi[r];
      for (int64_t v = begin; v < end; ++v)
        for (int k = 0; k < 3; ++k) {
          lo[k] = std::min(lo[k], rest_[v][k]);
          hi[k] = std::max(hi[k], rest_[v][k]);
        }
    });
    std::array<float, 3> lo = rest_[0], hi = rest_[0];
    for (int64_t r = 0; r < ranges; ++r)
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], range_lo[r][k]);
        hi[k] = std::max(hi[k], range_hi[r][k]);
      }
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (hi[k] - lo[k] > hi[axis] - lo[axis]) axis = k;
    const double thickness = kSlabVoxels * l_;
    Unfilled<int32_t> slab(nv);
    std::vector<int32_t> range_slabs(static_cast<size_t>(ranges), 1);
    ForEachRange(nv, [&](int64_t r, int64_t begin, int64_t end) {
      for (int64_t v = begin; v < end; ++v) {
        const double t = std::floor((static_cast<double>(rest_[v][axis]) - lo[axis]) / thickness);
        slab[v] = static_cast<int32_t>(std::clamp(t, 0.0, 1e6));
        range_slabs[r] = std::max(range_slabs[r], slab[v] + 1);
      }
    });
    int32_t slabs = *std::max_element(range_slabs.begin(), range_slabs.end());
    std::vector<char> range_spans(static_cast<size_t>(NumRanges(nf)), 0);
    ForEachRange(nf, [&](int64_t r, int64_t begin, int64_t end) {
      for (int64_t i = begin; i < end && !range_spans[r]; ++i) {
        const auto& f = mesh_.faces[i];
        const auto [a, b] = std::minmax({slab[f[0]], slab[f[1]], slab[f[2]]});
        range_spans[r] = b - a > 1;
      }
    });
    const bool one_slab =
        std::find(range_spans.begin(), range_spans.end(), 1) != range_spans.end();
    if (one_slab) slabs = 1;
    // Vertices by slab, stably: each range counts its vertices per slab; a range's vertices of
    // a slab go after those of earlier slabs and of earlier ranges in the same slab.
    std::vector<std::vector<int32_t>> count(static_cast<size_t>(ranges));
    ForEachRange(nv, [&](int64_t r, int64_t begin, int64_t end) {
      std::vector<int32_t>& c = count[r];
      c.assign(slabs, 0);
      for (int64_t v = begin; v < end; ++v) ++c[one_slab ? 0 : slab[v]];
    });
    slab_start_.assign(slabs + 1, 0);
    int32_t next = 0;
    for (int32_t k = 0; k < slabs; ++k) {
      slab_start_[k] = next;
      for (auto& c : count) {
        const int32_t here = c[k];
        c[k] = next;
        next += here;
      }
    }
    slab_start_[slabs] = next;
    slab_vertices_.resize(nv);
    ForEachRange(nv, [&](int64_t r, int64_t begin, int64_t end) {
      std::vector<int32_t>& c = count[r];
      for (int64_t v = begin; v < end; ++v)
        slab_vertices_[c[one_slab ? 0 : slab[v]]++] = static_cast<int32_t>(v);
    });
  }

  // Fits the slabs of one parity in one round, side by side on options_.threads. Returns false
  // when `cancel` fired (polled on the calling thread only); the phase's moves are then in
  // moved_ like the others.
  bool RunPhase(int round, int parity, const CancelToken& cancel, ProgressRange progress,
                FitStats& stats) {
    const int32_t slabs = static_cast<int32_t>(slab_start_.size()) - 1;
    const int32_t count = (slabs - parity + 1) / 2;
    if (cancel.cancelled()) return false;
    if (count <= 0) return true;
    std::vector<SlabWork> work(count);
    for (SlabWork& w : work) w.clock = clock_;
    TaskCancel stop(cancel, options_.threads, kCancelPollVertices);
    RunTasks(options_.threads, count, [&](int worker, int64_t task) {
      const int32_t s = parity + 2 * static_cast<int32_t>(task);
      SlabWork& w = work[task];
      for (int32_t i = slab_start_[s]; i < slab_start_[s + 1]; ++i) {
        if (stop.Poll(worker)) return;
        const int32_t v = slab_vertices_[i];
        // The weights change between the first round and the others; after that a vertex
        // whose target was already reached, and around which nothing moved since, would
        // compute the same target again.
        if (round >= 2 && Settled(v)) continue;
        FitVertex(v, round, w);
      }
      progress.Add(slab_start_[s + 1] - slab_start_[s]);
    });
    for (SlabWork& w : work) {
      clock_ = std::max(clock_, w.clock);
      stats.quadric_targets += w.stats.quadric_targets;
      stats.plane_targets += w.stats.plane_targets;
      stats.crease_targets += w.stats.crease_targets;
      stats.crease_line_targets += w.stats.crease_line_targets;
      stats.crease_tries += w.stats.crease_tries;
      stats.umbrella_targets += w.stats.umbrella_targets;
      stats.refused += w.stats.refused;
      moved_.insert(moved_.end(), w.moved.begin(), w.moved.end());
    }
    return !stop.fired() && !cancel.cancelled();
  }

  bool Settled(int32_t v) const {
    if (settled_at_[v] < 0) return false;
    for (int32_t i = star_start_[v]; i < star_start_[v + 1]; ++i)
      for (int32_t u : mesh_.faces[star_[i]])
        if (changed_at_[u] > settled_at_[v]) return false;
    return true;
  }

  Vec3d VertexNormal(int32_t v) const {
    Vec3d n{0, 0, 0};
    for (int32_t i = star_start_[v]; i < star_start_[v + 1]; ++i) {
      const Triangle3d t = Tri(star_[i]);
      n = n + TriangleNormal(t[0], t[1], t[2]);
    }
    const double len = Norm(n);
    return len > 0 ? (1.0 / len) * n : Vec3d{0, 0, 0};
  }

  // Mean of the 1-ring: around a closed fan every neighbour is in exactly two triangles.
  Vec3d RingMean(int32_t v) const {
    Vec3d sum{0, 0, 0};
    int count = 0;
    for (int32_t i = star_start_[v]; i < star_start_[v + 1]; ++i)
      for (int32_t u : mesh_.faces[star_[i]])
        if (u != v) {
          sum = sum + Pos(u);
          ++count;
        }
    return count > 0 ? (1.0 / count) * sum : Pos(v);
  }

  Vec3d Target(int32_t v, int round, SlabWork& w) const {
    FitStats& stats = w.stats;
    const Vec3d normal = VertexNormal(v);
    if (options_.quadric && SquaredNorm(normal) > 0) return CurvedTarget(v, round, normal, w);
    const Vec3d x = Pos(v);
    const double inv_2s2 = 1.0 / (2 * options_.sigma * options_.sigma * l_ * l_);
    // The first round's weights are isotropic.
    const double inv_2n2 =
        round >= 1 ? 1.0 / (2 * options_.normal_sigma * options_.normal_sigma * l_ * l_) : inv_2s2;
    const double radius = options_.search_radius * l_;
    NearPointWeights weights;
    weights.origin = mesh_.vertices[v];
    weights.radius2 = static_cast<float>(radius * radius);
    weights.inv_2s2 = static_cast<float>(inv_2s2);
    weights.inv_2n2 = static_cast<float>(inv_2n2);
    for (int k = 0; k < 3; ++k) weights.normal[k] = static_cast<float>(normal[k]);
    const NearPointResult near = WeighNearPoints(points_, radius, weights);
    const PlaneFitAccumulator& acc = near.acc;
    const int count = near.count;
    if (count >= options_.min_points && acc.weight() > 0) {
      ++stats.plane_targets;
      const auto plane = acc.Fit();
      // Points on a line or in a blob define no plane: slide along the vertex normal onto the
      // plane through their centroid instead.
      const Vec3d c = plane ? plane->centroid : (1.0 / acc.weight()) * acc.WeightedSum();
      const Vec3d n = plane ? plane->normal : normal;
      return x + Dot(c, n) * n;
    }
    ++stats.umbrella_targets;
    return x + options_.umbrella_step * (RingMean(v) - x);
  }

  // Target() with options_.quadric, for a vertex whose normal is `normal` (unit): the points
  // are weighed in the vertex's frame, in voxels; the quadric's height at the vertex moves it
  // along the normal. Where the quadric is not trusted, the plane of the same sums, as in
  // Target().
  Vec3d CurvedTarget(int32_t v, int round, const Vec3d& normal, SlabWork& w) const {
    FitStats& stats = w.stats;
    const Vec3d x = Pos(v);
    // An orthonormal tangent basis from the normal without a branch on its direction (Duff et
    // al., "Building an Orthonormal Basis, Revisited", 2017): the frame, and so the target,
    // depends on the normal alone.
    const double sign = std::copysign(1.0, normal[2]);
    const double p = -1.0 / (sign + normal[2]);
    const double q = normal[0] * normal[1] * p;
    const Vec3d t1{1 + sign * normal[0] * normal[0] * p, sign * q, -sign * normal[0]};
    const Vec3d t2{q, sign + normal[1] * normal[1] * p, -normal[1]};
    const Vec3d axes[3] = {t1, t2, normal};
    FrameWeights weights;
    weights.origin = mesh_.vertices[v];
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) weights.axes[i][k] = static_cast<float>(axes[i][k] / l_);
    // Along the normal the first round's weights are those across it; the sparse try widens
    // the weights across the normal only.
    const double ns = round >= 1 ? options_.normal_sigma : options_.sigma;
    weights.inv_2n2 = static_cast<float>(1.0 / (2 * ns * ns));
    const auto weigh = [&](double radius, double sigma) {
      weights.radius2 = static_cast<float>(radius * radius);
      weights.inv_2s2 = static_cast<float>(1.0 / (2 * sigma * sigma));
      return WeighNearPointsInFrame(points_, radius * l_, weights);
    };
    const HeightFieldSums sums = weigh(options_.search_radius, options_.sigma);
    if (sums.count >= options_.quadric_min_points) {
      const auto quadric = FitHeightQuadric(sums, options_.quadric_limits);
      // A quadric that leaves much unexplained, or bends past the limits, may be a crease's.
      if (options_.creases) {
        const auto raw = quadric ? quadric : SolveHeightQuadric(sums);
        const double rms = raw ? std::sqrt(QuadricMeanSquareResidual(sums, *raw)) : 0;
        if (raw && CreaseWorthTrying(rms, options_.crease_limits)) {
          CollectNearPointsInFrame(points_, options_.search_radius * l_, weights, w.near);
          ++stats.crease_tries;
          if (const auto crease = FitCrease(w.near, *raw, rms, options_.crease_limits)) {
            ++stats.crease_targets;
            stats.crease_line_targets += crease->on_line;
            const Vec3d& t = crease->target;
            return x + l_ * (t[0] * t1 + t[1] * t2 + t[2] * normal);
          }
        }
      }
      if (quadric) {
        ++stats.quadric_targets;
        return x + (quadric->height() * l_) * normal;
      }
    } else if (options_.sparse_radius > options_.search_radius) {
      const HeightFieldSums wide = weigh(options_.sparse_radius, options_.sparse_sigma);
      if (wide.count >= options_.quadric_min_points) {
        if (const auto quadric = FitHeightQuadric(wide, options_.quadric_limits)) {
          ++stats.quadric_targets;
          return x + (quadric->height() * l_) * normal;
        }
      }
    }
    if (sums.count < options_.min_points || !(sums.weight() > 0)) {
      ++stats.umbrella_targets;
      return x + options_.umbrella_step * (RingMean(v) - x);
    }
    ++stats.plane_targets;
    const PlaneFitAccumulator acc = sums.PlaneSums();
    const auto plane = acc.Fit();
    // In frame coordinates (voxels): the vertex is the origin, the normal (0, 0, 1).
    const Vec3d c = plane ? plane->centroid : (1.0 / acc.weight()) * acc.WeightedSum();
    const Vec3d n = plane ? plane->normal : Vec3d{0, 0, 1};
    const Vec3d local = Dot(c, n) * n;
    return x + l_ * (local[0] * t1 + local[1] * t2 + local[2] * normal);
  }

  // The checks that need only the vertex's own triangles: non-zero area, normal on the side of
  // the surface-nets normal, and no two of them overlapping.
  bool StarOk(int32_t v, const Point3f& candidate, SlabWork& w) const {
    const Vec3d c = ToVec3d(candidate);
    const int32_t begin = star_start_[v], end = star_start_[v + 1];
    std::vector<Triangle3d>& new_tri = w.new_tri;
    new_tri.clear();
    for (int32_t i = begin; i < end; ++i) {
      const int32_t f = star_[i];
      Triangle3d t = Tri(f);
      for (int k = 0; k < 3; ++k)
        if (mesh_.faces[f][k] == v) t[k] = c;
      if (!FaceOk(f, t)) return false;
      new_tri.push_back(t);
    }
    // The fast proof first; the pairs one by one only where it does not conclude.
    if (FanEmbeddedAt(v, c, w.ring_pos)) return true;
    const int32_t n = end - begin;
    for (int32_t i = 0; i < n; ++i)
      for (int32_t j = i + 1; j < n; ++j)
        if (MeshTrianglesIntersect(mesh_.faces[star_[begin + i]], new_tri[i],
                                   mesh_.faces[star_[begin + j]], new_tri[j]))
          return false;
    return true;
  }

  // FanIsEmbedded for v's fan with v at `centre`.
  bool FanEmbeddedAt(int32_t v, const Vec3d& centre, std::vector<Vec3d>& ring_pos) const {
    const absl::Span<const int32_t> ring = fans_.ring(v);
    if (ring.empty()) return false;
    ring_pos.clear();
    for (int32_t u : ring) ring_pos.push_back(Pos(u));
    return FanIsEmbedded(centre, ring_pos);
  }

  bool FaceOk(int32_t f, const Triangle3d& t) const {
    const Vec3d n = TriangleNormal(t[0], t[1], t[2]);
    return Norm(n) > min_double_area_ && Dot(n, rest_normal_[f]) > 0;
  }

  void FitVertex(int32_t v, int round, SlabWork& w) {
    settled_at_[v] = -1;
    const Vec3d x = Pos(v);
    Vec3d target = Target(v, round, w);
    const Vec3d rest = ToVec3d(rest_[v]);
    const Vec3d off = target - rest;
    const double max_off = options_.max_offset * l_;
    if (SquaredNorm(off) > max_off * max_off) target = rest + (max_off / Norm(off)) * off;
    const Vec3d delta = target - x;
    if (SquaredNorm(delta) < options_.min_move * options_.min_move * l_ * l_) {
      settled_at_[v] = w.clock;
      return;
    }
    for (int level = 0; level < kFullyBackedOff; ++level) {
      const Point3f candidate = Place(x + kStepFractions[level] * delta);
      if (candidate == mesh_.vertices[v]) break;
      if (StarOk(v, candidate, w)) {
        if (!in_round_[v]) {
          start_[v] = mesh_.vertices[v];
          in_round_[v] = 1;
          w.moved.push_back(v);
        }
        target_[v] = ToVec3d(candidate);
        level_[v] = 0;
        backed_off_[v] = level > 0;
        Set(v, candidate, w.clock);
        return;
      }
    }
    settled_at_[v] = w.clock;
    ++w.stats.refused;
  }

  // Ends the fit: searches the faces around the moved vertices for pairs that intersect (on the
  // float32 positions that are written: this is also the rounding check of step 6) and backs
  // the moved vertices of such pairs off, from their final position toward where they started,
  // through the step fractions, then all the way, until nothing crosses. A back-off can leave
  // a triangle inverted next to a vertex that moved later; its moved vertices then go back to
  // their start too. One search after all rounds instead of one per move: a linear pass rather
  // than a grid query per vertex, with the same guarantee; crossings are rare (tens of pairs
  // per 300k faces), so backing off whole moves loses little.
  //
  // Each search covers every pair with a face around a vertex changed since the last one, and
  // the pairs that last one found: so after each search `pairs` lists every crossing of the
  // mesh once the first search covered it all. Without the carried pairs a crossing whose
  // vertices cannot move (the input's, found beside crossings of moves) would drop out of the
  // search unrepaired.
  //
  // Once a search covered the whole mesh, `pairs` is every crossing, and a carried pair whose
  // faces did not change since still crosses: it is kept without being searched again, and the
  // search covers the faces around changed vertices alone. On a coarse output grid tens of
  // thousands of crossings can wait for the fallback while a few vertices back off per search;
  // searching their faces again each time made the searches' cost follow the crossings (about
  // the whole mesh) instead of the changes.
  void Verify(bool search_all, FitStats& stats) {
    if (moved_.empty() && !search_all) return;
    std::vector<int32_t> changed = moved_;
    std::vector<std::pair<int32_t, int32_t>> pairs, kept;
    for (bool first = true;; first = false) {
      const bool every_face = first && search_all;
      std::fill(dirty_.begin(), dirty_.end(), every_face ? 1 : 0);
      // Every face is marked already on a first search of all: the moved vertices' stars (most
      // of the mesh) need no pass of their own.
      if (!every_face)
        for (int32_t v : changed)
          for (int32_t i = star_start_[v]; i < star_start_[v + 1]; ++i) dirty_[star_[i]] = 1;
      if (search_all) {
        kept.clear();
        for (const auto& p : pairs)
          if (!dirty_[p.first] && !dirty_[p.second]) kept.push_back(p);
      } else {
        for (const auto& [a, b] : pairs) dirty_[a] = dirty_[b] = 1;
      }
      pairs = FindIntersectingFacesNear(mesh_, dirty_, options_.threads, &blocks_);
      if (!kept.empty()) {
        // Disjoint sorted lists: the found pairs have a dirty face, the kept ones none.
        std::vector<std::pair<int32_t, int32_t>> all(pairs.size() + kept.size());
        std::merge(pairs.begin(), pairs.end(), kept.begin(), kept.end(), all.begin());
        pairs = std::move(all);
      }
      if (pairs.empty()) break;
      changed.clear();
      for (const auto& [a, b] : pairs)
        for (int32_t f : {a, b})
          for (int32_t v : mesh_.faces[f])
            if (IsMoved(v) && mesh_.vertices[v] != start_[v]) changed.push_back(v);
      std::sort(changed.begin(), changed.end());
      changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
      if (changed.empty()) {
        // Every vertex of the crossing pairs is where the pass found it: the input crossed.
        if (!RepairTowardFallback(pairs, changed)) break;  // nothing left to move
        stats.repaired_vertices += static_cast<int64_t>(changed.size());
        continue;
      }
      for (int32_t v : changed) BackOff(v);
      // Inverted or collapsed triangles next to backed-off vertices: send their moved
      // vertices home as well, until every such triangle is fine.
      for (size_t k = 0; k < changed.size(); ++k) {
        const int32_t v = changed[k];
        for (int32_t i = star_start_[v]; i < star_start_[v + 1]; ++i) {
          const int32_t f = star_[i];
          if (FaceOk(f, Tri(f))) continue;
          for (int32_t u : mesh_.faces[f])
            if (IsMoved(u) && mesh_.vertices[u] != start_[u]) {
              level_[u] = kFullyBackedOff;
              Set(u, start_[u], clock_);
              changed.push_back(u);
            }
        }
      }
    }
    for (int32_t v : moved_) {
      if (mesh_.vertices[v] != start_[v]) {
        ++stats.moves;
      } else {
        ++stats.refused;
      }
      if (level_[v] > 0 || backed_off_[v]) ++stats.backed_off;
    }
    for (int32_t v : moved_) in_round_[v] = 0;
    moved_.clear();
    if (search_all) {
      stats.crossings_known = true;
      stats.crossings = std::move(pairs);
    }
  }

  bool IsMoved(int32_t v) const { return in_round_[v] != 0; }

  // Moves the vertices of `pairs` toward their fallback positions (halfway, then all the way
  // after 6 halvings) and makes the new positions their input positions. Fills `moved`;
  // returns false when nothing could move (no fallback, or all there already).
  bool RepairTowardFallback(const std::vector<std::pair<int32_t, int32_t>>& pairs,
                            std::vector<int32_t>& moved) {
    moved.clear();
    if (fallback_ == nullptr) return false;
    for (const auto& [a, b] : pairs)
      for (int32_t f : {a, b})
        for (int32_t v : mesh_.faces[f]) moved.push_back(v);
    std::sort(moved.begin(), moved.end());
    moved.erase(std::unique(moved.begin(), moved.end()), moved.end());
    size_t kept = 0;
    for (int32_t v : moved) {
      const Point3f safe = grid_.Snap((*fallback_)[v]);
      if (mesh_.vertices[v] == safe) continue;
      const double keep = repair_level_[v]++ < kRepairHalvings ? 0.5 : 0.0;
      const Vec3d s = ToVec3d(safe);
      const Point3f p = Place(s + keep * (Pos(v) - s));
      Set(v, p, clock_);
      rest_[v] = p;
      start_[v] = p;
      moved[kept++] = v;
    }
    moved.resize(kept);
    for (int32_t v : moved)
      for (int32_t i = star_start_[v]; i < star_start_[v + 1]; ++i) {
        const Triangle3d t = Tri(star_[i]);
        rest_normal_[star_[i]] = TriangleNormal(t[0], t[1], t[2]);
      }
    return !moved.empty();
  }

  // The next fraction of the way from start to target, or the start.
  void BackOff(int32_t v) {
    ++level_[v];
    const Vec3d s = ToVec3d(start_[v]);
    const double f = level_[v] < kFullyBackedOff ? kStepFractions[level_[v]] : 0.0;
    Set(v, f > 0 ? Place(s + f * (target_[v] - s)) : start_[v], clock_);
  }

  TriangleMesh& mesh_;
  const double l_;
  const FitOptions options_;
  const std::vector<Point3f>* fallback_;
  const PositionGrid grid_;
  // Input positions (the clamp's centre); they move only when repaired toward the fallback.
  Unfilled<Point3f> rest_;
  const MeshFans fans_;
  Unfilled<uint8_t> repair_level_;
  const PointRowGrid points_;
  StarArray star_start_, star_;
  Unfilled<Vec3d> rest_normal_;
  double min_double_area_ = 0;
  // Move clock: changed_at_[v] = clock value of v's last change; settled_at_[v] = clock value
  // when v last found its target already reached or refused (-1: not settled). Each slab of a
  // phase counts from clock_ on its own (a vertex's ring is in its slab or in slabs of the
  // other parity, fitted in another phase); clock_ then moves past them all.
  int64_t clock_ = 0;
  Unfilled<int64_t> changed_at_, settled_at_;
  // The moved vertices: position before their first move, last applied position, back-off
  // level in the final check, and whether the last move was taken short of its target.
  std::vector<int32_t> moved_;
  Unfilled<char> in_round_, backed_off_;
  Unfilled<Point3f> start_;
  Unfilled<Vec3d> target_;  // last applied position
  Unfilled<int> level_;
  std::vector<char> dirty_;
  // Boxes of runs of faces, for the searches around dirty faces: each search marks the faces
  // around every vertex changed since the last one, as FaceBlockBoxes requires.
  FaceBlockBoxes blocks_;
  // The slabs' vertices, slab by slab (AssignSlabs).
  std::vector<int32_t> slab_start_;
  Unfilled<int32_t> slab_vertices_;
};

absl::Status ValidateOptions(double voxel_size, const FitOptions& o) {
  if (!(voxel_size > 0) || !std::isfinite(voxel_size))
    return absl::InvalidArgumentError(absl::StrCat("voxel size ", voxel_size, " is not positive"));
  if (o.rounds < 0 || !(o.search_radius > 0) || !(o.sigma > 0) || !(o.normal_sigma > 0) ||
      o.min_points < 3 || o.quadric_min_points < 6 ||
      !(o.quadric_limits.min_tangent_spread >= 0) || !(o.quadric_limits.max_slope >= 0) ||
      !(o.quadric_limits.max_centroid_offset >= 0) ||
      !(o.quadric_limits.max_curvature >= 0) || !(o.umbrella_step >= 0 && o.umbrella_step <= 1) ||
      !(o.sparse_radius >= 0) || !(o.sparse_sigma > 0) || !(o.max_offset >= 0) ||
      !(o.dense_points_per_vertex >= 0) || o.mean_split < 1 || o.mean_split > 8 ||
      !(o.min_move >= 0) || o.output_grid.bits < 0 || o.output_grid.bits > 30 ||
      !(o.output_grid.box.range > 0) || !std::isfinite(o.output_grid.box.range))
    return absl::InvalidArgumentError(
        absl::StrCat("fit options out of range: rounds ", o.rounds, ", search_radius ",
                     o.search_radius, ", sigma ", o.sigma, ", normal_sigma ", o.normal_sigma,
                     ", min_points ", o.min_points, ", quadric_min_points ",
                     o.quadric_min_points, ", quadric limits (spread, centroid, slope, bend) ",
                     o.quadric_limits.min_tangent_spread, ", ",
                     o.quadric_limits.max_centroid_offset, ", ", o.quadric_limits.max_slope, ", ",
                     o.quadric_limits.max_curvature, ", sparse_radius ", o.sparse_radius,
                     ", sparse_sigma ", o.sparse_sigma, ", dense_points_per_vertex ",
                     o.dense_points_per_vertex, ", mean_split ", o.mean_split,
                     ", umbrella_step ", o.umbrella_step,
                     ", max_offset ", o.max_offset, ", min_move ", o.min_move,
                     ", output grid bits ", o.output_grid.bits, " range ", o.output_grid.box.range));
  const CreaseLimits& c = o.crease_limits;
  if (!(c.min_quadric_rms >= 0) || !(c.max_rms_ratio >= 0) ||
      !(c.min_angle_degrees >= 0 && c.min_angle_degrees <= 180) || c.min_side_points < 3 ||
      !(c.min_side_share >= 0 && c.min_side_share <= 0.5) || !(c.snap_distance >= 0) ||
      !(c.noise >= 0) || !std::isfinite(c.noise) || !(c.noise_trigger >= 0) ||
      !(c.noise_accept >= 0) || !(c.max_noisy_ratio >= 0))
    return absl::InvalidArgumentError(absl::StrCat(
        "crease limits out of range: min_quadric_rms ", c.min_quadric_rms, ", max_rms_ratio ",
        c.max_rms_ratio, ", min_angle_degrees ", c.min_angle_degrees, ", min_side_points ",
        c.min_side_points, ", min_side_share ", c.min_side_share, ", snap_distance ",
        c.snap_distance, ", noise ", c.noise, ", noise_trigger ", c.noise_trigger,
        ", noise_accept ", c.noise_accept, ", max_noisy_ratio ", c.max_noisy_ratio));
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<FitStats> FitToPoints(TriangleMesh& mesh, double voxel_size,
                                     absl::Span<const Point3f> points, const FitOptions& options,
                                     const CancelToken& cancel,
                                     const std::vector<Point3f>* fallback,
                                     ProgressRange progress,
                                     std::optional<PointRowGrid> points_grid) {
  if (absl::Status s = ValidateOptions(voxel_size, options); !s.ok()) return s;
  FitStats stats;
  if (mesh.faces.empty()) {
    progress.Done();
    return stats;
  }
  if (fallback != nullptr && fallback->size() != mesh.vertices.size())
    return absl::InvalidArgumentError(absl::StrCat(
        "fallback has ", fallback->size(), " positions for ", mesh.vertices.size(), " vertices"));
  Fitter fitter(mesh, voxel_size,
                BuildIndexes(mesh, voxel_size, points, options, std::move(points_grid)), options,
                fallback);
  stats.weighed_points = fitter.weighed_points();
  if (absl::Status s = fitter.Run(cancel, progress, stats); !s.ok()) return s;
  return stats;
}

}  // namespace membrane

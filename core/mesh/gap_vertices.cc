#include "core/mesh/gap_vertices.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstdint>
#include <optional>

#include "absl/status/status.h"
#include "core/base/parallel_tasks.h"
#include "core/geometry/vec3.h"

namespace membrane {
namespace {

// Vertices a task: enough that a task's queries outweigh handing it out, few enough that two
// threads end together on a 100k-vertex mesh.
constexpr int64_t kBlockVertices = 4096;

}  // namespace

absl::StatusOr<GapVertices> FindGapVertices(const TriangleMesh& mesh,
                                            absl::Span<const Point3f> points, double radius,
                                            int last_bin, bool collect_remote,
                                            int64_t remote_min_count, int threads,
                                            const CancelToken& cancel,
                                            const PointRowGrid* shared) {
  const int64_t nv = static_cast<int64_t>(mesh.vertices.size());
  GapVertices out;
  out.gap.assign(nv, 0);
  out.histogram.assign(last_bin + 1, 0);
  const double r2 = radius * radius;
  std::optional<PointRowGrid> own;
  if (shared == nullptr) own.emplace(points, radius, threads);
  const PointRowGrid& grid = shared != nullptr ? *shared : *own;
  const float* px = grid.xs();
  const float* py = grid.ys();
  const float* pz = grid.zs();
  const int workers = std::max(threads, 1);
  const int64_t tasks = (nv + kBlockVertices - 1) / kBlockVertices;
  // Per worker: integer sums, the same whatever tasks each worker ran.
  std::vector<int64_t> counts(workers, 0);
  std::vector<std::vector<int64_t>> histograms(workers, std::vector<int64_t>(last_bin + 1, 0));
  TaskCancel task_cancel(cancel, workers, 1);
  // Calls visit(worker, v) for every vertex, in blocks on the threads, until a cancel.
  const auto each_vertex = [&](auto&& visit) {
    RunTasks(threads, tasks, [&](int worker, int64_t task) {
      if (task_cancel.Poll(worker)) return;
      const int64_t end = std::min(nv, (task + 1) * kBlockVertices);
      for (int64_t v = task * kBlockVertices; v < end; ++v) visit(worker, v);
    });
  };
  // The counts first, each vertex's stopping at last_bin points: a mesh with too few gaps (most
  // meshes) needs nothing more, and a vertex on dense data stops after a few of the dozens of
  // points in its ball.
  each_vertex([&](int worker, int64_t v) {
    int near = 0;
    const Vec3d c = ToVec3d(mesh.vertices[v]);
    grid.ForEachRun(c, radius, [&](uint32_t begin, uint32_t stop) {
      for (uint32_t i = begin; i < stop && near < last_bin; ++i) {
        const double dx = px[i] - c[0], dy = py[i] - c[1], dz = pz[i] - c[2];
        near += dx * dx + dy * dy + dz * dz <= r2;
      }
    });
    out.gap[v] = near == 0;
    counts[worker] += near == 0;
    if (near > 0) ++histograms[worker][std::min(near, last_bin)];
  });
  if (task_cancel.fired()) return absl::CancelledError("hole caps cancelled");
  for (int w = 0; w < workers; ++w) {
    out.count += counts[w];
    for (int k = 0; k <= last_bin; ++k) out.histogram[k] += histograms[w][k];
  }
  if (!collect_remote || out.count < remote_min_count) return out;
  // Then the points some vertex covers. A bit a point, set by whichever vertex sees it first
  // (an atomic or): the union does not depend on the order. Only the points no vertex has
  // covered yet are weighed, found a word of bits at a time (on a dense cloud most of a
  // vertex's points are covered by its neighbours).
  std::vector<std::atomic<uint64_t>> covered((grid.num_points() + 63) / 64);
  each_vertex([&](int, int64_t v) {
    const Vec3d c = ToVec3d(mesh.vertices[v]);
    grid.ForEachRun(c, radius, [&](uint32_t begin, uint32_t stop) {
      uint64_t i = begin;
      while (i < stop) {
        const uint64_t open = ~covered[i >> 6].load(std::memory_order_relaxed) >> (i & 63);
        if (open == 0) {
          i = (i | 63) + 1;
          continue;
        }
        i += static_cast<uint64_t>(std::countr_zero(open));
        if (i >= stop) break;
        const double dx = px[i] - c[0], dy = py[i] - c[1], dz = pz[i] - c[2];
        if (dx * dx + dy * dy + dz * dz <= r2) {
          covered[i >> 6].fetch_or(uint64_t{1} << (i & 63), std::memory_order_relaxed);
        }
        ++i;
      }
    });
  });
  if (task_cancel.fired()) return absl::CancelledError("hole caps cancelled");
  for (size_t i = 0; i < grid.num_points(); ++i)
    if (((covered[i >> 6].load(std::memory_order_relaxed) >> (i & 63)) & 1) == 0)
      out.remote.push_back(Point3f{px[i], py[i], pz[i]});
  return out;
}

}  // namespace membrane

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
  // A bit a point, set by whichever vertex sees it first (an atomic or): the union does not
  // depend on the order. Bits, so that a vertex passes over 64 points some vertex already
  // covered with one load.
  std::vector<std::atomic<uint64_t>> covered(collect_remote ? (grid.num_points() + 63) / 64 : 0);
  const auto mark = [&](uint64_t i) {
    std::atomic<uint64_t>& word = covered[i >> 6];
    const uint64_t bit = uint64_t{1} << (i & 63);
    if ((word.load(std::memory_order_relaxed) & bit) == 0)
      word.fetch_or(bit, std::memory_order_relaxed);
  };
  const float* px = grid.xs();
  const float* py = grid.ys();
  const float* pz = grid.zs();
  const int workers = std::max(threads, 1);
  // Per worker: integer sums, the same whatever tasks each worker ran.
  std::vector<int64_t> counts(workers, 0);
  std::vector<std::vector<int64_t>> histograms(workers, std::vector<int64_t>(last_bin + 1, 0));
  TaskCancel task_cancel(cancel, workers, 1);
  const int64_t tasks = (nv + kBlockVertices - 1) / kBlockVertices;
  RunTasks(threads, tasks, [&](int worker, int64_t task) {
    if (task_cancel.Poll(worker)) return;
    const int64_t end = std::min(nv, (task + 1) * kBlockVertices);
    for (int64_t v = task * kBlockVertices; v < end; ++v) {
      int near = 0;
      const Vec3d c = ToVec3d(mesh.vertices[v]);
      const auto inside = [&](uint64_t i) {
        const double dx = px[i] - c[0], dy = py[i] - c[1], dz = pz[i] - c[2];
        return dx * dx + dy * dy + dz * dz <= r2;
      };
      grid.ForEachRun(c, radius, [&](uint32_t begin, uint32_t stop) {
        uint64_t i = begin;
        for (; i < stop && near < last_bin; ++i)
          if (inside(i)) {
            ++near;
            if (collect_remote) mark(i);
          }
        if (!collect_remote) return;
        // Past last_bin the count is not needed, and a covered point stays covered: only the
        // points no vertex has covered yet are weighed, found a word of bits at a time (on a
        // dense cloud most of a vertex's points are covered by its neighbours).
        while (i < stop) {
          const uint64_t open = ~covered[i >> 6].load(std::memory_order_relaxed) >> (i & 63);
          if (open == 0) {
            i = (i | 63) + 1;
            continue;
          }
          i += static_cast<uint64_t>(std::countr_zero(open));
          if (i >= stop) break;
          if (inside(i)) mark(i);
          ++i;
        }
      });
      out.gap[v] = near == 0;
      counts[worker] += near == 0;
      if (near > 0) ++histograms[worker][std::min(near, last_bin)];
    }
  });
  if (task_cancel.fired()) return absl::CancelledError("hole caps cancelled");
  for (int w = 0; w < workers; ++w) {
    out.count += counts[w];
    for (int k = 0; k <= last_bin; ++k) out.histogram[k] += histograms[w][k];
  }
  if (collect_remote && out.count >= remote_min_count)
    for (size_t i = 0; i < grid.num_points(); ++i)
      if (((covered[i >> 6].load(std::memory_order_relaxed) >> (i & 63)) & 1) == 0)
        out.remote.push_back(Point3f{px[i], py[i], pz[i]});
  return out;
}

}  // namespace membrane

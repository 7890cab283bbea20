#include "core/mesh/gap_vertices.h"

#include <algorithm>
#include <atomic>
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
  // A point is marked by whichever vertex sees it first; every mark writes the same 1, so the
  // union does not depend on the order (relaxed atomic bytes: plain stores on x86).
  std::vector<char> covered(collect_remote ? grid.num_points() : 0, 0);
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
      grid.ForEachRun(c, radius, [&](uint32_t begin, uint32_t stop) {
        for (uint32_t i = begin; i < stop; ++i) {
          // Past last_bin the count is not needed, and a point some vertex already covers
          // stays covered: on a dense cloud most of a vertex's points are then one byte read.
          const bool count = near < last_bin;
          if (!count && (!collect_remote ||
                         std::atomic_ref<char>(covered[i]).load(std::memory_order_relaxed)))
            continue;
          const double dx = px[i] - c[0], dy = py[i] - c[1], dz = pz[i] - c[2];
          if (dx * dx + dy * dy + dz * dz <= r2) {
            near += count;
            if (collect_remote)
              std::atomic_ref<char>(covered[i]).store(1, std::memory_order_relaxed);
          }
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
      if (!covered[i]) out.remote.push_back(Point3f{px[i], py[i], pz[i]});
  return out;
}

}  // namespace membrane

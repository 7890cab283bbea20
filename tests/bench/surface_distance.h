// Accuracy of a reconstructed mesh against a reference mesh: area-uniform samples of each
// surface, exact point-to-triangle distances (BVH), symmetric Chamfer, p95, Hausdorff, F-score.
#ifndef MEMBRANE_TESTS_BENCH_SURFACE_DISTANCE_H_
#define MEMBRANE_TESTS_BENCH_SURFACE_DISTANCE_H_

#include <array>
#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "core/geometry/triangle_mesh.h"

namespace membrane::bench {

using Vec3d = std::array<double, 3>;

// Exact distance queries to the triangles of a mesh: a bounding-volume hierarchy (median split
// on the longest axis, leaves of <= 4 triangles) searched nearest box first. Degenerate
// triangles are kept (their distance is still exact); faces with out-of-range indices skipped.
class TriangleDistance {
 public:
  // Builds the hierarchy: O(F log F). `mesh` is copied (as doubles); it need not outlive this.
  explicit TriangleDistance(const TriangleMesh& mesh);

  bool empty() const { return tris_.empty(); }
  // Unsigned distance from `p` to the nearest triangle; +infinity when there is none.
  double Distance(const Vec3d& p) const;

 private:
  struct Node {
    Vec3d lo, hi;
    int32_t first = 0, count = 0;  // leaf: triangles [first, first + count); else count = 0
    int32_t left = -1, right = -1;
  };
  int32_t Build(int32_t first, int32_t count, std::vector<Vec3d>& centroids);

  std::vector<std::array<Vec3d, 3>> tris_;
  std::vector<Node> nodes_;
};

// `count` points on `mesh`, uniform by area (triangle chosen with probability proportional to
// its area, then a uniform barycentric point), from a fixed-seed generator: deterministic.
// Empty when the mesh has no area.
std::vector<Vec3d> SampleSurface(const TriangleMesh& mesh, int64_t count, uint64_t seed);

struct SurfaceDistances {
  double diagonal = 0;      // bounding-box diagonal of the reference mesh (model units)
  // All as % of `diagonal`:
  double chamfer = 0;       // (mean d(recon -> ref) + mean d(ref -> recon)) / 2
  double to_reference = 0;  // mean d(recon samples -> reference surface)
  double to_recon = 0;      // mean d(reference samples -> reconstruction)
  double p95 = 0;           // 95th percentile of both directions' distances pooled
  double hausdorff = 0;     // max of both directions (over the samples)
  // F-score at threshold tau = fscore_tau % of the diagonal: precision = share of recon samples
  // within tau of the reference, recall = share of reference samples within tau of the recon.
  double fscore_tau = 1.0;
  double precision = 0, recall = 0, fscore = 0;  // fractions in [0, 1]
};

// Compares `recon` with `reference` on `samples` area-uniform samples of each (seeded, so
// repeatable). InvalidArgument when either mesh has no area. `fscore_tau_percent` is tau as %
// of the reference diagonal.
absl::StatusOr<SurfaceDistances> CompareSurfaces(const TriangleMesh& recon,
                                                 const TriangleMesh& reference,
                                                 int64_t samples = 100'000,
                                                 double fscore_tau_percent = 1.0);

}  // namespace membrane::bench

#endif  // MEMBRANE_TESTS_BENCH_SURFACE_DISTANCE_H_

// Self-intersection search over a whole mesh: a uniform-grid broad phase and the predicates of
// triangle_intersection.h. Used by the mesh check (count) and by the last step of the point
// fitting (membrane-quality.md recipe 3 step 6: re-check every triangle after rounding).
#ifndef MEMBRANE_CORE_MESH_SELF_INTERSECTION_H_
#define MEMBRANE_CORE_MESH_SELF_INTERSECTION_H_

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/base/cancel_token.h"
#include "core/base/progress_meter.h"
#include "core/geometry/triangle_mesh.h"
#include "core/mesh/face_grid.h"

namespace membrane {

// All pairs (i, j), i < j, of faces of `mesh` that intersect in the sense of
// MeshTrianglesIntersect (any contact between faces without a common vertex; only non-trivial
// overlaps between faces that share a vertex or an edge). Faces with an index out of range are
// skipped. Sorted by (i, j). Each pair is reported once.
// Cost: O(F) cells and entries; the cell size follows the mean face size, and the cell count is
// bounded by a few times F, so huge faces cost more entries, never quadratic memory. A cell
// of more than 512 faces (faces far smaller than the mean crowded together) is split into
// width classes and sub-cells, so its pairs tried follow the faces that overlap, not the
// square of its count.
// `cancel` is polled every few thousand cells, on the calling thread only; once it fires the
// pairs found so far are returned. `threads` (<= 1: the calling thread alone) share the cells;
// the result does not depend on it. `progress` counts the cells' entries as they are walked
// and reaches its end with the search.
std::vector<std::pair<int32_t, int32_t>> FindIntersectingFaces(
    const TriangleMesh& mesh, const CancelToken& cancel = CancelToken::Never(), int threads = 1,
    ProgressRange progress = ProgressRange());

// Bounding boxes of runs of kFaces consecutive faces, kept by a caller that searches the same
// mesh again and again while moving a few of its vertices (the fit's last step): the search
// around a few dirty faces then skips the runs far from all of them without reading their
// faces. Faces are in spatial order (MortonOrder), so a run is a small patch.
class FaceBlockBoxes {
 public:
  static constexpr int32_t kFaces = 64;
  using Box = FaceBox;

  // Makes every run's box when the mesh's face count differs from the last call's (or on the
  // first), else remakes the boxes of the runs holding a face marked in `dirty` (one flag per
  // face). Contract: every face whose vertices moved since the last call is marked. Faces with
  // an index out of range are left out. Ranges of runs go to `threads` (<= 1: the calling
  // thread); each run's box is the same for any count.
  void Update(const TriangleMesh& mesh, const std::vector<char>& dirty, int threads = 1);

  int32_t size() const { return static_cast<int32_t>(boxes_.size()); }
  const Box& box(int32_t block) const { return boxes_[block]; }

 private:
  void Remake(const TriangleMesh& mesh, int32_t block);
  std::vector<Box> boxes_;
  size_t faces_ = 0;
};

// The same, restricted to pairs with at least one face marked in `dirty` (one flag per face):
// after moving a few vertices, the pairs that may have changed. Costs a linear scan of the
// faces plus the pair search around the dirty ones; with `blocks` (updated here, see
// FaceBlockBoxes::Update for its contract), a scan of the runs' boxes and of the faces of runs
// near a dirty face instead. The result does not depend on `blocks` or `threads`.
std::vector<std::pair<int32_t, int32_t>> FindIntersectingFacesNear(
    const TriangleMesh& mesh, const std::vector<char>& dirty, int threads = 1,
    FaceBlockBoxes* blocks = nullptr);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_SELF_INTERSECTION_H_

// A uniform grid of triangle bounding boxes that faces can be added to one by one: the
// broad phase of the local self-intersection test of each edge collapse (mesh_decimation.h).
// Entries are never removed: a face that moved is added again where it now lies, and the
// stale entries it leaves are candidates the caller rejects by the face's current box. Each
// entry holds the face's box as inserted, so that a search tests boxes in the order they lie
// in memory and reads the mesh only for faces whose box overlaps its own. The
// decimation rebuilds the grid, with larger cells, as its faces grow.
#ifndef MEMBRANE_CORE_MESH_FACE_GRID_H_
#define MEMBRANE_CORE_MESH_FACE_GRID_H_

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/types/span.h"
#include "core/geometry/triangle_mesh.h"

namespace membrane {

// An axis-aligned box, model units.
struct FaceBox {
  std::array<float, 3> lo, hi;
};

// The bounding box of face `f` of `mesh` (indices valid).
FaceBox BoxOfFace(const TriangleMesh& mesh, int32_t f);
// True when the closed boxes share a point.
inline bool BoxesOverlap(const FaceBox& a, const FaceBox& b) {
  for (int k = 0; k < 3; ++k)
    if (a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k]) return false;
  return true;
}

class FaceGrid {
 public:
  // Cells of side `cell` model units (> 0, finite).
  explicit FaceGrid(double cell);

  // Enters `face` in every cell its `box` overlaps (a face spanning more than 4096 cells goes
  // on a list every query returns instead).
  void Insert(int32_t face, const FaceBox& box);

  // Calls visit(face) for every entry of the cells `box` overlaps, and of the list of large
  // faces, whose box as inserted overlaps `box`: a superset of the faces whose last inserted
  // box overlaps it. A face may come more than once, and faces removed or moved since an
  // insertion come too.
  template <typename Visit>
  void ForEachCandidate(const FaceBox& box, Visit&& visit) const {
    std::array<int64_t, 3> lo, hi;
    CellRange(box, lo, hi);
    for (int64_t z = lo[2]; z <= hi[2]; ++z)
      for (int64_t y = lo[1]; y <= hi[1]; ++y)
        for (int64_t x = lo[0]; x <= hi[0]; ++x) {
          const auto it = cells_.find(Key(x, y, z));
          if (it == cells_.end()) continue;
          for (const Entry& e : it->second)
            if (BoxesOverlap(e.box, box)) visit(e.face);
        }
    for (const Entry& e : large_)
      if (BoxesOverlap(e.box, box)) visit(e.face);
  }

  // The same for a set of boxes: every entry, of the cells one of `boxes` overlaps, whose box
  // overlaps `bound` (a box holding all of them); each cell once. Reads fewer cells than a
  // search of `bound` when the boxes are a fan around a point. `cells` is scratch.
  template <typename Visit>
  void ForEachCandidateOf(absl::Span<const FaceBox> boxes, const FaceBox& bound,
                          std::vector<uint64_t>& cells, Visit&& visit) const {
    cells.clear();
    for (const FaceBox& box : boxes) {
      std::array<int64_t, 3> lo, hi;
      CellRange(box, lo, hi);
      for (int64_t z = lo[2]; z <= hi[2]; ++z)
        for (int64_t y = lo[1]; y <= hi[1]; ++y)
          for (int64_t x = lo[0]; x <= hi[0]; ++x) cells.push_back(Key(x, y, z));
    }
    std::sort(cells.begin(), cells.end());
    cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
    for (uint64_t key : cells) {
      const auto it = cells_.find(key);
      if (it == cells_.end()) continue;
      for (const Entry& e : it->second)
        if (BoxesOverlap(e.box, bound)) visit(e.face);
    }
    for (const Entry& e : large_)
      if (BoxesOverlap(e.box, bound)) visit(e.face);
  }

  double cell() const { return cell_; }
  int64_t entries() const { return entries_; }

 private:
  struct Entry {
    FaceBox box;
    int32_t face;
  };
  void CellRange(const FaceBox& box, std::array<int64_t, 3>& lo,
                 std::array<int64_t, 3>& hi) const;
  // 21 bits per axis; cells whose coordinates agree modulo 2^21 share a key, which only adds
  // candidates.
  static uint64_t Key(int64_t x, int64_t y, int64_t z) {
    constexpr uint64_t kMask = (uint64_t{1} << 21) - 1;
    return (static_cast<uint64_t>(x) & kMask) | (static_cast<uint64_t>(y) & kMask) << 21 |
           (static_cast<uint64_t>(z) & kMask) << 42;
  }

  double cell_;
  double inverse_cell_;
  absl::flat_hash_map<uint64_t, std::vector<Entry>> cells_;
  std::vector<Entry> large_;
  int64_t entries_ = 0;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_FACE_GRID_H_

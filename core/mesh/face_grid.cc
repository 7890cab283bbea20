#include "core/mesh/face_grid.h"

#include <algorithm>
#include <cmath>

namespace membrane {

FaceBox BoxOfFace(const TriangleMesh& mesh, int32_t f) {
  FaceBox b;
  b.lo = b.hi = mesh.vertices[mesh.faces[f][0]];
  for (int k = 1; k < 3; ++k) {
    const Point3f& p = mesh.vertices[mesh.faces[f][k]];
    for (int a = 0; a < 3; ++a) {
      b.lo[a] = std::min(b.lo[a], p[a]);
      b.hi[a] = std::max(b.hi[a], p[a]);
    }
  }
  return b;
}

FaceGrid::FaceGrid(double cell) : cell_(cell), inverse_cell_(1 / cell) {}

void FaceGrid::CellRange(const FaceBox& box, std::array<int64_t, 3>& lo,
                         std::array<int64_t, 3>& hi) const {
  for (int k = 0; k < 3; ++k) {
    lo[k] = static_cast<int64_t>(std::floor(box.lo[k] * inverse_cell_));
    hi[k] = static_cast<int64_t>(std::floor(box.hi[k] * inverse_cell_));
  }
}

void FaceGrid::Insert(int32_t face, const FaceBox& box) {
  std::array<int64_t, 3> lo, hi;
  CellRange(box, lo, hi);
  const int64_t span = (hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1);
  ++entries_;
  if (span > 4096) {
    large_.push_back({box, face});
    return;
  }
  entries_ += span - 1;
  for (int64_t z = lo[2]; z <= hi[2]; ++z)
    for (int64_t y = lo[1]; y <= hi[1]; ++y)
      for (int64_t x = lo[0]; x <= hi[0]; ++x) cells_[Key(x, y, z)].push_back({box, face});
}

}  // namespace membrane

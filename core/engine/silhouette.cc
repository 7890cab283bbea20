#include "core/engine/silhouette.h"

#include <vector>

namespace membrane {
namespace {

// A 2-D coverage image of one axis projection, dilated by one pixel (3x3).
struct Projection {
  int w = 0, h = 0;
  std::vector<uint8_t> px;
  bool at(int i, int j) const { return px[static_cast<size_t>(i + w * j)] != 0; }
  void Dilate() {
    std::vector<uint8_t> out(px.size(), 0);
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        if (!at(i, j)) continue;
        for (int dj = -1; dj <= 1; ++dj)
          for (int di = -1; di <= 1; ++di) {
            const int a = i + di, b = j + dj;
            if (a >= 0 && b >= 0 && a < w && b < h) out[static_cast<size_t>(a + w * b)] = 1;
          }
      }
    px.swap(out);
  }
};

}  // namespace

int64_t SilhouettePreshrink(VoxelGrid& grid) {
  const auto& d = grid.dims();
  // proj[a] is the projection along axis a onto the other two axes (b, c) = (a+1, a+2) % 3.
  Projection proj[3];
  for (int a = 0; a < 3; ++a) {
    proj[a].w = d[(a + 1) % 3];
    proj[a].h = d[(a + 2) % 3];
    proj[a].px.assign(static_cast<size_t>(proj[a].w) * proj[a].h, 0);
  }
  for (int z = 0; z < d[2]; ++z)
    for (int y = 0; y < d[1]; ++y)
      for (int x = 0; x < d[0]; ++x) {
        if (!IsHard(grid.at(grid.Index(x, y, z)))) continue;
        const int c[3] = {x, y, z};
        for (int a = 0; a < 3; ++a)
          proj[a].px[static_cast<size_t>(c[(a + 1) % 3] + proj[a].w * c[(a + 2) % 3])] = 1;
      }
  for (Projection& p : proj) p.Dilate();

  int64_t carved = 0;
  for (int z = 0; z < d[2]; ++z)
    for (int y = 0; y < d[1]; ++y)
      for (int x = 0; x < d[0]; ++x) {
        const int64_t i = grid.Index(x, y, z);
        if (IsOutside(grid.at(i))) continue;
        const int c[3] = {x, y, z};
        bool covered = true;
        for (int a = 0; a < 3 && covered; ++a)
          covered = proj[a].at(c[(a + 1) % 3], c[(a + 2) % 3]);
        if (!covered) {
          grid.set(i, OutsideState(0));
          ++carved;
        }
      }
  // The new membrane: every non-outside voxel touching outside (26-adjacency) is boundary.
  const std::array<int64_t, 27>& offsets = grid.block_offsets();
  VoxelState* s = grid.mutable_states().data();
  for (int z = 1; z + 1 < d[2]; ++z)
    for (int y = 1; y + 1 < d[1]; ++y)
      for (int x = 1; x + 1 < d[0]; ++x) {
        const int64_t i = grid.Index(x, y, z);
        if (!IsInside(s[i])) continue;
        for (int64_t offset : offsets)
          if (IsOutside(s[i + offset])) {
            s[i] |= kBoundaryBit;
            break;
          }
      }
  return carved;
}

}  // namespace membrane

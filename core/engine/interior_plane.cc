#include "core/engine/interior_plane.h"

namespace membrane {

FlatBitset InteriorPlane(const std::array<int, 3>& d) {
  // Rows of ones from x = 1 to nx - 2, set a word at a time.
  FlatBitset plane(static_cast<int64_t>(d[0]) * d[1] * d[2]);
  for (int z = 1; z + 1 < d[2]; ++z)
    for (int y = 1; y + 1 < d[1]; ++y) {
      int64_t i = d[0] * (y + static_cast<int64_t>(d[1]) * z) + 1;
      const int64_t end = i + d[0] - 2;
      uint64_t* w = plane.words();
      while (i < end && (i & 63) != 0) plane.set(i++);
      for (; i + 64 <= end; i += 64) w[i >> 6] = ~0ull;
      while (i < end) plane.set(i++);
    }
  return plane;
}

namespace {

// Clears bits [begin, end), whole words where it can.
void ClearRange(int64_t begin, int64_t end, FlatBitset& plane) {
  uint64_t* w = plane.words();
  int64_t i = begin;
  while (i < end && (i & 63) != 0) plane.reset(i++);
  for (; i + 64 <= end; i += 64) w[i >> 6] = 0;
  while (i < end) plane.reset(i++);
}

}  // namespace

void ClearArrayBorder(const std::array<int, 3>& d, FlatBitset& plane) {
  const int64_t nx = d[0], ny = d[1], nz = d[2];
  const int64_t slab = nx * ny;
  if (nx == 0 || ny == 0 || nz == 0) return;
  ClearRange(0, slab, plane);                    // z = 0
  ClearRange((nz - 1) * slab, nz * slab, plane);  // z = nz - 1
  for (int64_t z = 1; z + 1 < nz; ++z) {
    const int64_t base = z * slab;
    ClearRange(base, base + nx, plane);                       // y = 0
    ClearRange(base + (ny - 1) * nx, base + slab, plane);     // y = ny - 1
    for (int64_t y = 1; y + 1 < ny; ++y) {
      plane.reset(base + y * nx);           // x = 0
      plane.reset(base + y * nx + nx - 1);  // x = nx - 1
    }
  }
}

}  // namespace membrane

#include "core/engine/local_topology.h"

#include <bit>

namespace membrane {
namespace {

// Bits whose x (y, z) offset is not +1, resp. not -1: they may step that way without
// leaving the block.
constexpr uint32_t AxisNot(int axis, int value) {
  uint32_t m = 0;
  for (int b = 0; b < 27; ++b) {
    int c[3] = {b % 3, (b / 3) % 3, b / 9};
    if (c[axis] != value) m |= 1u << b;
  }
  return m;
}
constexpr uint32_t kNotX2 = AxisNot(0, 2), kNotX0 = AxisNot(0, 0);
constexpr uint32_t kNotY2 = AxisNot(1, 2), kNotY0 = AxisNot(1, 0);
constexpr uint32_t kNotZ2 = AxisNot(2, 2), kNotZ0 = AxisNot(2, 0);

constexpr uint32_t Grow6(uint32_t s) {
  return s | ((s & kNotX2) << 1) | ((s & kNotX0) >> 1) | ((s & kNotY2) << 3) |
         ((s & kNotY0) >> 3) | ((s & kNotZ2) << 9) | ((s & kNotZ0) >> 9);
}
constexpr uint32_t Grow26(uint32_t s) {
  s |= ((s & kNotX2) << 1) | ((s & kNotX0) >> 1);
  s |= ((s & kNotY2) << 3) | ((s & kNotY0) >> 3);
  s |= ((s & kNotZ2) << 9) | ((s & kNotZ0) >> 9);
  return s;
}

constexpr uint32_t MakeFaceMask() {
  return (1u << NeighbourBit(-1, 0, 0)) | (1u << NeighbourBit(1, 0, 0)) |
         (1u << NeighbourBit(0, -1, 0)) | (1u << NeighbourBit(0, 1, 0)) |
         (1u << NeighbourBit(0, 0, -1)) | (1u << NeighbourBit(0, 0, 1));
}
constexpr uint32_t MakeN18Mask() {
  uint32_t m = 0;
  for (int b = 0; b < 27; ++b) {
    int nonzero = (b % 3 != 1) + ((b / 3) % 3 != 1) + (b / 9 != 1);
    if (nonzero == 1 || nonzero == 2) m |= 1u << b;
  }
  return m;
}
constexpr uint32_t kFaceMask = MakeFaceMask();
constexpr uint32_t kN18Mask = MakeN18Mask();

}  // namespace

uint32_t FaceNeighboursMask() { return kFaceMask; }
uint32_t N18Mask() { return kN18Mask; }

uint32_t OutsideMask(const VoxelGrid& grid, int64_t index) {
  return NeighbourhoodMask(grid, index, [](VoxelState s) { return IsOutside(s); });
}

uint32_t Flood6(uint32_t seed, uint32_t allowed) {
  uint32_t reach = seed & allowed;
  for (;;) {
    uint32_t next = Grow6(reach) & allowed;
    if (next == reach) return reach;
    reach = next;
  }
}

uint32_t Flood26(uint32_t seed, uint32_t allowed) {
  uint32_t reach = seed & allowed;
  for (;;) {
    uint32_t next = Grow26(reach) & allowed;
    if (next == reach) return reach;
    reach = next;
  }
}

int CountT6(uint32_t background) {
  uint32_t rest = background & kN18Mask;
  int count = 0;
  uint32_t faces = rest & kFaceMask;
  while (faces != 0) {
    uint32_t seed = faces & (~faces + 1);
    uint32_t comp = Flood6(seed, rest);
    ++count;
    rest &= ~comp;
    faces &= ~comp;
  }
  return count;
}

int CountT26(uint32_t object) {
  uint32_t rest = object & kAll27 & ~kCentreBit;
  int count = 0;
  while (rest != 0) {
    uint32_t seed = rest & (~rest + 1);
    rest &= ~Flood26(seed, rest);
    ++count;
  }
  return count;
}

bool IsSimple(uint32_t object) {
  return CountT26(object) == 1 && CountT6(~object & kAll27) == 1;
}

}  // namespace membrane

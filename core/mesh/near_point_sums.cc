#include "core/mesh/near_point_sums.h"

#include <bit>
#include <cstring>

#include "core/mesh/fast_exp.h"

namespace membrane {
namespace {

// Four points per step (fast_exp.h's V4f): the compiler did not vectorize the same loop written
// over lane arrays (it ran slower than the scalar double code).
constexpr int kLanes = 4;
static_assert(PointRowGrid::kTail + 1 >= kLanes, "a run's last step may read kLanes - 1 past it");

V4f Load(const float* p) {
  V4f v;
  std::memcpy(&v, p, sizeof(v));
  return v;
}

float Sum(V4f v) { return (v[0] + v[1]) + (v[2] + v[3]); }

}  // namespace

NearPointResult WeighNearPoints(const PointRowGrid& grid, double radius,
                                const NearPointWeights& weights) {
  const V4f ox = SplatV4f(weights.origin[0]), oy = SplatV4f(weights.origin[1]),
            oz = SplatV4f(weights.origin[2]);
  const V4f nx = SplatV4f(weights.normal[0]), ny = SplatV4f(weights.normal[1]),
            nz = SplatV4f(weights.normal[2]);
  const V4f r2 = SplatV4f(weights.radius2);
  // e = (|d|^2 - dn^2) a + dn^2 b = |d|^2 a + dn^2 (b - a).
  const V4f a = SplatV4f(weights.inv_2s2), b_minus_a = SplatV4f(weights.inv_2n2 - weights.inv_2s2);
  const V4i lane = {0, 1, 2, 3};
  const V4f zero = SplatV4f(0);
  V4f sw = zero, sx = zero, sy = zero, sz = zero;
  V4f sxx = zero, sxy = zero, sxz = zero, syy = zero, syz = zero, szz = zero;
  V4i count = {0, 0, 0, 0};
  const float* xs = grid.xs();
  const float* ys = grid.ys();
  const float* zs = grid.zs();
  const Vec3d centre{weights.origin[0], weights.origin[1], weights.origin[2]};
  grid.ForEachRun(centre, radius, [&](uint32_t begin, uint32_t end) {
    for (uint32_t i = begin; i < end; i += kLanes) {
      const V4f dx = Load(xs + i) - ox, dy = Load(ys + i) - oy, dz = Load(zs + i) - oz;
      const V4f d2 = dx * dx + dy * dy + dz * dz;
      const V4f dn = dx * nx + dy * ny + dz * nz;
      // -1 in the lanes that hold a point of this run within the radius, 0 elsewhere.
      const V4i inside = (d2 <= r2) & (lane < static_cast<int32_t>(end - i));
      const V4f w = std::bit_cast<V4f>(std::bit_cast<V4i>(ExpNeg4(d2 * a + dn * dn * b_minus_a)) &
                                       inside);
      count -= inside;
      sw += w;
      const V4f wx = w * dx, wy = w * dy, wz = w * dz;
      sx += wx;
      sy += wy;
      sz += wz;
      sxx += wx * dx;
      sxy += wx * dy;
      sxz += wx * dz;
      syy += wy * dy;
      syz += wy * dz;
      szz += wz * dz;
    }
  });
  NearPointResult out;
  out.count = count[0] + count[1] + count[2] + count[3];
  out.acc = PlaneFitAccumulator::FromSums(
      Sum(sw), {Sum(sx), Sum(sy), Sum(sz)},
      {Sum(sxx), Sum(sxy), Sum(sxz), Sum(syy), Sum(syz), Sum(szz)});
  return out;
}

}  // namespace membrane

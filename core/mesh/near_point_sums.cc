#include "core/mesh/near_point_sums.h"

#include <bit>
#include <cmath>
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

// Whether any lane of a comparison's mask is set.
bool AnyLane(V4i mask) {
  uint64_t half[2];
  std::memcpy(half, &mask, sizeof(half));
  return (half[0] | half[1]) != 0;
}

// The points' counts: one a lane inside (kWeighted false), or the sum of the stored weights
// of the lanes inside (a grid of cell means, whose weights are their points' counts).
template <bool kWeighted>
struct LaneCounts {
  V4i ones = {0, 0, 0, 0};
  V4f weights = SplatV4f(0);
  // Adds the lanes of `inside` (-1 inside, 0 outside); `w` the lanes' stored weights.
  void Add(V4i inside, V4f w) {
    if constexpr (kWeighted) {
      weights += std::bit_cast<V4f>(std::bit_cast<V4i>(w) & inside);
    } else {
      ones -= inside;
    }
  }
  // Counts the lanes of `inside` and returns the weights `w` of points ws[i..i+3], each times
  // the point's stored weight when the grid holds cell means (its points' count).
  V4f Weigh(V4f w, V4i inside, [[maybe_unused]] const float* ws, [[maybe_unused]] uint32_t i) {
    if constexpr (kWeighted) {
      const V4f c = Load(ws + i);
      Add(inside, c);
      return w * c;
    } else {
      Add(inside, SplatV4f(0));
      return w;
    }
  }
  // The counts are whole numbers under 2^24 in each lane: float sums them exactly.
  int Total() const {
    if constexpr (kWeighted) return static_cast<int>(Sum(weights));
    return ones[0] + ones[1] + ones[2] + ones[3];
  }
};

template <bool kWeighted>
[[gnu::always_inline]] inline NearPointResult WeighNear(const PointRowGrid& grid, double radius,
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
  LaneCounts<kWeighted> count;
  const float* xs = grid.xs();
  const float* ys = grid.ys();
  const float* zs = grid.zs();
  const float* ws = grid.ws();
  const Vec3d centre{weights.origin[0], weights.origin[1], weights.origin[2]};
  grid.ForEachRun(centre, radius, [&](uint32_t begin, uint32_t end) {
    for (uint32_t i = begin; i < end; i += kLanes) {
      const V4f dx = Load(xs + i) - ox, dy = Load(ys + i) - oy, dz = Load(zs + i) - oz;
      const V4f d2 = dx * dx + dy * dy + dz * dz;
      const V4f dn = dx * nx + dy * ny + dz * nz;
      // -1 in the lanes that hold a point of this run within the radius, 0 elsewhere.
      const V4i inside = (d2 <= r2) & (lane < static_cast<int32_t>(end - i));
      if (!AnyLane(inside)) continue;  // see WeighNearPointsInFrame
      const V4f w = count.Weigh(
          std::bit_cast<V4f>(std::bit_cast<V4i>(ExpNeg4(d2 * a + dn * dn * b_minus_a)) & inside),
          inside, ws, i);
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
  out.count = count.Total();
  out.acc = PlaneFitAccumulator::FromSums(
      Sum(sw), {Sum(sx), Sum(sy), Sum(sz)},
      {Sum(sxx), Sum(sxy), Sum(sxz), Sum(syy), Sum(syz), Sum(szz)});
  return out;
}

template <bool kWeighted>
[[gnu::always_inline]] inline HeightFieldSums WeighInFrame(const PointRowGrid& grid, double radius,
                                                           const FrameWeights& weights) {
  const V4f ox = SplatV4f(weights.origin[0]), oy = SplatV4f(weights.origin[1]),
            oz = SplatV4f(weights.origin[2]);
  V4f ax[3][3];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) ax[i][k] = SplatV4f(weights.axes[i][k]);
  const V4f r2 = SplatV4f(weights.radius2);
  const V4f a = SplatV4f(weights.inv_2s2), b = SplatV4f(weights.inv_2n2);
  const V4i lane = {0, 1, 2, 3};
  const V4f zero = SplatV4f(0);
  // The 15 moments of u^i v^j, then the 6 of h u^i v^j, then h^2 (HeightFieldSums' order).
  V4f m[15], hm[6], shh = zero;
  for (V4f& x : m) x = zero;
  for (V4f& x : hm) x = zero;
  LaneCounts<kWeighted> count;
  const float* xs = grid.xs();
  const float* ys = grid.ys();
  const float* zs = grid.zs();
  const float* ws = grid.ws();
  const Vec3d centre{weights.origin[0], weights.origin[1], weights.origin[2]};
  grid.ForEachRun(centre, radius, [&](uint32_t begin, uint32_t end) {
    for (uint32_t i = begin; i < end; i += kLanes) {
      const V4f dx = Load(xs + i) - ox, dy = Load(ys + i) - oy, dz = Load(zs + i) - oz;
      const V4f u = dx * ax[0][0] + dy * ax[0][1] + dz * ax[0][2];
      const V4f v = dx * ax[1][0] + dy * ax[1][1] + dz * ax[1][2];
      const V4f h = dx * ax[2][0] + dy * ax[2][1] + dz * ax[2][2];
      const V4f uu = u * u, uv = u * v, vv = v * v, h2 = h * h;
      const V4f t2 = uu + vv;
      const V4i inside = (t2 + h2 <= r2) & (lane < static_cast<int32_t>(end - i));
      // Half the steps hold no point of the ball (the box's corners). Skipping them leaves
      // every sum's bits as they are: a masked lane adds a zero, and a lane's sum, never -0
      // (it starts at +0 and round-to-nearest cancels to +0), is unchanged by adding one.
      if (!AnyLane(inside)) continue;
      const V4f w = count.Weigh(
          std::bit_cast<V4f>(std::bit_cast<V4i>(ExpNeg4(t2 * a + h2 * b)) & inside), inside, ws, i);
      const V4f wu = w * u, wv = w * v, wuu = w * uu, wvv = w * vv, wuv = w * uv, wh = w * h;
      m[0] += w;
      m[1] += wu;
      m[2] += wv;
      m[3] += wuu;
      m[4] += wuv;
      m[5] += wvv;
      m[6] += wuu * u;
      m[7] += wuu * v;
      m[8] += wvv * u;
      m[9] += wvv * v;
      m[10] += wuu * uu;
      m[11] += wuu * uv;
      m[12] += wuu * vv;
      m[13] += wvv * uv;
      m[14] += wvv * vv;
      hm[0] += wh;
      hm[1] += wh * u;
      hm[2] += wh * v;
      hm[3] += wh * uu;
      hm[4] += wh * uv;
      hm[5] += wh * vv;
      shh += wh * h;
    }
  });
  HeightFieldSums out;
  out.count = count.Total();
  for (int k = 0; k < 15; ++k) out.uv[k] = Sum(m[k]);
  for (int k = 0; k < 6; ++k) out.huv[k] = Sum(hm[k]);
  out.hh = Sum(shh);
  return out;
}

// Each weighing compiled for the baseline instruction set and, on x86-64, once more for
// AVX-512 (F, VL): its 32 vector registers hold the 22 sums, the frame and the constants that
// the baseline's 16 keep spilling to the stack. Every operation is the same IEEE one in both
// (the file is compiled without contracting a * b + c into a fused multiply-add), so the sums
// have the same bits on any processor.
template <bool kWeighted>
NearPointResult NearBaseline(const PointRowGrid& grid, double radius, const NearPointWeights& w) {
  return WeighNear<kWeighted>(grid, radius, w);
}
template <bool kWeighted>
HeightFieldSums InFrameBaseline(const PointRowGrid& grid, double radius, const FrameWeights& w) {
  return WeighInFrame<kWeighted>(grid, radius, w);
}

#if defined(__x86_64__) && defined(__GNUC__)
#define MEMBRANE_WIDE_TARGET "avx512f,avx512vl"
template <bool kWeighted>
[[gnu::target(MEMBRANE_WIDE_TARGET), gnu::flatten]] NearPointResult NearWide(
    const PointRowGrid& grid, double radius, const NearPointWeights& w) {
  return WeighNear<kWeighted>(grid, radius, w);
}
template <bool kWeighted>
[[gnu::target(MEMBRANE_WIDE_TARGET), gnu::flatten]] HeightFieldSums InFrameWide(
    const PointRowGrid& grid, double radius, const FrameWeights& w) {
  return WeighInFrame<kWeighted>(grid, radius, w);
}
bool UseWide(SumsInstructions instructions) {
  return instructions == SumsInstructions::kBest && __builtin_cpu_supports("avx512f") &&
         __builtin_cpu_supports("avx512vl");
}
#else
bool UseWide(SumsInstructions) { return false; }
#endif

}  // namespace

bool HasWideSumsInstructions() { return UseWide(SumsInstructions::kBest); }

NearPointResult WeighNearPoints(const PointRowGrid& grid, double radius,
                                const NearPointWeights& weights, SumsInstructions instructions) {
  const bool weighted = grid.ws() != nullptr;
  if (UseWide(instructions)) {
#ifdef MEMBRANE_WIDE_TARGET
    return weighted ? NearWide<true>(grid, radius, weights)
                    : NearWide<false>(grid, radius, weights);
#endif
  }
  return weighted ? NearBaseline<true>(grid, radius, weights)
                  : NearBaseline<false>(grid, radius, weights);
}

HeightFieldSums WeighNearPointsInFrame(const PointRowGrid& grid, double radius,
                                       const FrameWeights& weights, SumsInstructions instructions) {
  const bool weighted = grid.ws() != nullptr;
  if (UseWide(instructions)) {
#ifdef MEMBRANE_WIDE_TARGET
    return weighted ? InFrameWide<true>(grid, radius, weights)
                    : InFrameWide<false>(grid, radius, weights);
#endif
  }
  return weighted ? InFrameBaseline<true>(grid, radius, weights)
                  : InFrameBaseline<false>(grid, radius, weights);
}

void CollectNearPointsInFrame(const PointRowGrid& grid, double radius, const FrameWeights& weights,
                              std::vector<FramePoint>& out) {
  out.clear();
  const float* xs = grid.xs();
  const float* ys = grid.ys();
  const float* zs = grid.zs();
  const float* ws = grid.ws();
  const auto& ax = weights.axes;
  const Vec3d centre{weights.origin[0], weights.origin[1], weights.origin[2]};
  grid.ForEachRun(centre, radius, [&](uint32_t begin, uint32_t end) {
    for (uint32_t i = begin; i < end; ++i) {
      const double dx = xs[i] - weights.origin[0], dy = ys[i] - weights.origin[1],
                   dz = zs[i] - weights.origin[2];
      FramePoint p;
      p.u = dx * ax[0][0] + dy * ax[0][1] + dz * ax[0][2];
      p.v = dx * ax[1][0] + dy * ax[1][1] + dz * ax[1][2];
      p.h = dx * ax[2][0] + dy * ax[2][1] + dz * ax[2][2];
      const double t2 = p.u * p.u + p.v * p.v, h2 = p.h * p.h;
      if (t2 + h2 > weights.radius2) continue;
      p.w = std::exp(-t2 * weights.inv_2s2 - h2 * weights.inv_2n2) * (ws ? ws[i] : 1.0f);
      if (p.w > 0) out.push_back(p);
    }
  });
}

}  // namespace membrane

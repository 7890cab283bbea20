// The grid a quantized encoding puts positions on: Draco's position quantization, computed the
// way Draco computes it, so that a mesh whose vertices were snapped here is exactly the mesh a
// decoder gets back. The surface snaps its vertices while it is built and the mesh check
// then judges the very positions that are delivered (the check of float positions said nothing
// about the file: 11-bit rounding made faces cross on 9 of the 10 real clouds).
#ifndef MEMBRANE_CORE_GEOMETRY_POSITION_GRID_H_
#define MEMBRANE_CORE_GEOMETRY_POSITION_GRID_H_

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/geometry/point_cloud.h"

namespace membrane {

// The box a grid spans: [origin, origin + range] on every axis.
struct PositionBox {
  std::array<float, 3> origin{0, 0, 0};
  float range = 1;  // the side of the (cubic) box
};

// Draco hands an explicit quantization box to its encoder through its options, which store
// numbers as std::to_string text (six decimals) and parse them back: a box value survives
// only if that round trip returns it. (Found the hard way: origins off by up to 3e-7 moved
// every decoded vertex off the grid the mesh was checked on, and made faces cross.)
inline float DecimalRoundTrip(float v) { return std::strtof(std::to_string(v).c_str(), nullptr); }

// A float within a millionth (and a float step) of `x`, on the side asked for (at or below it
// when `lower`, else at or above), that DecimalRoundTrip keeps.
inline float DecimalSafeBound(double x, bool lower) {
  const double dir = lower ? -1 : 1;
  double decimal = (lower ? std::floor(x * 1e6) : std::ceil(x * 1e6)) / 1e6;
  float f = static_cast<float>(decimal);
  // Small magnitudes: the float of a six-decimal number round-trips, and float rounding may
  // cross x by a step. Large ones: every float round-trips; step float by float.
  for (int i = 0; i < 100000; ++i) {
    const bool on_side = lower ? f <= x : f >= x;
    if (on_side && DecimalRoundTrip(f) == f) return f;
    if (DecimalRoundTrip(f) == f) {
      f = std::nextafter(f, static_cast<float>(dir * HUGE_VALF));
    } else {
      decimal += dir * 1e-6;
      f = static_cast<float>(decimal);
    }
  }
  return f;  // not reached for finite x
}

// bits == 0: no grid, positions are kept as float32 (lossless). Otherwise each coordinate c is
// stored as an integer q in [0, 2^bits - 1] and decoded as box.origin[c] + q * step, step =
// box.range / (2^bits - 1), the same range on every axis (as Draco does).
struct PositionGrid {
  int bits = 0;
  PositionBox box;

  bool lossless() const { return bits == 0; }
  int32_t max_quantized() const { return static_cast<int32_t>((int64_t{1} << bits) - 1); }
  double step() const { return lossless() ? 0.0 : static_cast<double>(box.range) / max_quantized(); }

  // Draco's quantizer scale, max_quantized / range, in float (Quantizer::Init).
  float InverseDelta() const { return static_cast<float>(max_quantized()) / box.range; }

  // What Draco rounds (floor(x + 0.5)) to the integer of coordinate `v` on `axis`: the offset
  // from the origin times `inverse_delta` (InverseDelta()), in Draco's float operations.
  float Scaled(float v, int axis, float inverse_delta) const {
    float offset = v - box.origin[axis];
    offset *= inverse_delta;
    return offset;
  }

  // The position a Draco decoder returns for `p` encoded on this grid (`p` itself when
  // lossless). The float operations are Draco's own (Quantizer and Dequantizer of
  // draco/core/quantization_utils.h and AttributeQuantizationTransform), in the same order;
  // a snapped position snaps to itself. Coordinates outside the grid's box are clamped to it.
  Point3f Snap(const Point3f& p) const {
    if (lossless()) return p;
    const int32_t max_q = max_quantized();
    const float inverse_delta = InverseDelta();
    const float delta = box.range / static_cast<float>(max_q);
    Point3f out;
    for (int c = 0; c < 3; ++c) {
      float v = Scaled(p[c], c, inverse_delta);
      // Clamped before the conversion (which a value out of int32's range would make
      // undefined); inside the box this changes nothing.
      v = v > 0 ? std::min(v, static_cast<float>(max_q)) : 0.0f;
      const int32_t q = static_cast<int32_t>(std::floor(v + 0.5f));
      out[c] = static_cast<float>(q) * delta + box.origin[c];
    }
    return out;
  }
};

// The grid of `bits` whose box holds [low, high] on every axis, its range widened by
// `margin` (relative) and at least 1e-6, with box values that survive Draco's option text
// (DecimalSafeBound), so that Snap gives what a decoder returns.
inline PositionGrid GridOverBox(int bits, const std::array<double, 3>& low,
                                const std::array<double, 3>& high, double margin) {
  PositionGrid grid;
  grid.bits = bits;
  double side = 0;
  for (int k = 0; k < 3; ++k) {
    grid.box.origin[k] = DecimalSafeBound(low[k], /*lower=*/true);
    side = std::max(side, high[k] - grid.box.origin[k]);
  }
  // A flat or single-point box still needs a positive range.
  grid.box.range = DecimalSafeBound(std::max(side * (1 + margin), 1e-6), /*lower=*/false);
  return grid;
}

// The grid of `bits` over the bounding box of `points` (non-empty, finite), as Draco would
// choose it (the largest side as the range) but text-safe (GridOverBox).
inline PositionGrid BoundingGrid(const std::vector<Point3f>& points, int bits) {
  std::array<float, 3> low = points.front(), high = points.front();
  for (const Point3f& p : points)
    for (int k = 0; k < 3; ++k) {
      low[k] = std::min(low[k], p[k]);
      high[k] = std::max(high[k], p[k]);
    }
  return GridOverBox(bits, {low[0], low[1], low[2]}, {high[0], high[1], high[2]}, 0.0);
}

}  // namespace membrane

#endif  // MEMBRANE_CORE_GEOMETRY_POSITION_GRID_H_

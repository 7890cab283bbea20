// A weighted least-squares height field h = f + d u + e v + a u^2 + b u v + c v^2 over the
// points near one surface vertex, in a frame (u, v tangent, h along the vertex normal) centred
// on the vertex: the fit's curved target (point_fitting.h). A plane through points sampled
// from a curved surface lies inside the convex side; the quadric follows the curvature, so a
// vertex projected onto it is not pulled inward on convex parts nor outward on concave ones.
#ifndef MEMBRANE_CORE_MESH_HEIGHT_QUADRIC_H_
#define MEMBRANE_CORE_MESH_HEIGHT_QUADRIC_H_

#include <array>
#include <optional>

#include "core/mesh/plane_fit.h"

namespace membrane {

// Weighted sums over points (u, v, h) in a vertex's frame, in voxels.
struct HeightFieldSums {
  // Index of the moment u^i v^j (i + j <= 4) in `uv`, and of h u^i v^j (i + j <= 2) in `huv`:
  // degree by degree, by the power of v within a degree.
  static constexpr int Index(int i, int j) { return (i + j) * (i + j + 1) / 2 + j; }
  std::array<double, 15> uv{};  // sum of w u^i v^j; uv[0] is the total weight
  std::array<double, 6> huv{};  // sum of w h u^i v^j
  double hh = 0;                // sum of w h^2
  int count = 0;                // points counted

  double weight() const { return uv[0]; }
  // The same points' plane sums, with (u, v, h) as coordinates.
  PlaneFitAccumulator PlaneSums() const;
};

// When a quadric is not to be trusted (the caller then fits a plane).
struct HeightQuadricLimits {
  // The points' spread across the tangent plane, in voxels: the smaller standard deviation of
  // the weighted (u, v) must reach this, so that the quadratic terms are not extrapolated
  // from a strip of points.
  double min_tangent_spread = 0.3;
  // The weighted centroid of (u, v) within this many of those standard deviations of the
  // vertex: a vertex beyond the points' footprint (past a data hole's rim, say) would be
  // placed by extrapolation.
  double max_centroid_offset = 1.0;
  // The fitted surface's slope at the vertex (|grad h|): steeper means the frame is far from
  // the surface's tangent plane and a height field over it is a poor model.
  double max_slope = 1.0;
  // Second derivatives (|h_uu|, |h_vv|, |h_uv|), per voxel: bends sharper than this are the
  // two sheets of a thin part or noise, not a surface that the voxels resolve.
  double max_curvature = 1.5;
};

struct HeightQuadric {
  // f, d, e, a, b, c: h = f + d u + e v + a u^2 + b u v + c v^2.
  std::array<double, 6> coefficients{};
  double height() const { return coefficients[0]; }  // h at the vertex (u = v = 0)
};

// The weighted least-squares quadric of `sums` whatever its shape, or nullopt when the normal
// equations are singular (or the weight is zero).
std::optional<HeightQuadric> SolveHeightQuadric(const HeightFieldSums& sums);

// The weighted mean square of the points' heights about `q`, the least-squares quadric of the
// same `sums` (sum w h^2 - c . sum w h phi, divided by the weight; 0 for no weight).
double QuadricMeanSquareResidual(const HeightFieldSums& sums, const HeightQuadric& q);

// The weighted least-squares quadric of `sums`, or nullopt when the weight is zero, the
// normal equations are singular, or it breaks `limits`.
std::optional<HeightQuadric> FitHeightQuadric(const HeightFieldSums& sums,
                                              const HeightQuadricLimits& limits);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_HEIGHT_QUADRIC_H_

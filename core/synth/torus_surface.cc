#include "core/synth/torus_surface.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/synth/synth_random.h"

namespace membrane {
namespace {

class TorusSurface : public SurfaceSampler {
 public:
  TorusSurface()
      : axis_(TorusAxis()),
        e1_(Normalized(Cross(axis_, {0.0, 0.0, 1.0}))),
        e2_(Cross(axis_, e1_)) {}

  SurfaceSample Sample(std::mt19937_64& rng) const override {
    constexpr double R = kTorusMajorRadius, r = kTorusMinorRadius;
    const double u = 2.0 * std::numbers::pi * Uniform01(rng);
    // The area element is r (R + r cos v) du dv: accept v with probability
    // (R + r cos v) / (R + r), so the outer side gets its larger share; R / (R + r) = 61% of
    // the draws are accepted.
    double v;
    do {
      v = 2.0 * std::numbers::pi * Uniform01(rng);
    } while ((R + r) * Uniform01(rng) > R + r * std::cos(v));
    const Vec3d radial = std::cos(u) * e1_ + std::sin(u) * e2_;
    const Vec3d normal = std::cos(v) * radial + std::sin(v) * axis_;
    return {R * radial + r * normal, normal};
  }

  Interval ExtentAlong(const Vec3d& d) const override {
    // Support function: the centre circle reaches R |d projected on the ring's plane|, the
    // tube adds r.
    const double along_axis = Dot(axis_, d);
    const double h =
        kTorusMajorRadius * std::sqrt(std::max(0.0, 1.0 - along_axis * along_axis)) +
        kTorusMinorRadius;
    return {-h, h};
  }

 private:
  Vec3d axis_, e1_, e2_;  // right-handed frame: e1, e2 span the ring's plane
};

}  // namespace

Vec3d TorusAxis() { return Normalized({1.0, 1.0, 1.0}); }

std::unique_ptr<SurfaceSampler> MakeTiltedTorus() { return std::make_unique<TorusSurface>(); }

}  // namespace membrane

#include "core/synth/sphere_surfaces.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/synth/synth_random.h"

namespace membrane {
namespace {

// A sphere, optionally without the cap above local height `max_z` (in radii, in [-1, 1]).
class SphereSurface : public SurfaceSampler {
 public:
  SphereSurface(const Vec3d& centre, double radius, double max_z = 1.0)
      : centre_(centre), radius_(radius), max_z_(max_z) {}

  SurfaceSample Sample(std::mt19937_64& rng) const override {
    // Archimedes: on a sphere, area is proportional to height, so a uniform height in
    // [-1, max_z] is area-uniform on the capped sphere too, without rejection.
    const double z = -1.0 + (1.0 + max_z_) * Uniform01(rng);
    const double phi = 2.0 * std::numbers::pi * Uniform01(rng);
    const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
    const Vec3d n = {s * std::cos(phi), s * std::sin(phi), z};
    return {centre_ + radius_ * n, n};
  }

  Interval ExtentAlong(const Vec3d& d) const override {
    const double c = Dot(centre_, d);
    return {c - radius_, c + radius_};
  }

 private:
  Vec3d centre_;
  double radius_;
  double max_z_;
};

class TwoSpheresSurface : public SurfaceSampler {
 public:
  TwoSpheresSurface() : a_(TwoSpheresCentres()[0], 1.0), b_(TwoSpheresCentres()[1], 1.0) {}

  SurfaceSample Sample(std::mt19937_64& rng) const override {
    return Uniform01(rng) < 0.5 ? a_.Sample(rng) : b_.Sample(rng);
  }

  Interval ExtentAlong(const Vec3d& d) const override {
    const Interval a = a_.ExtentAlong(d), b = b_.ExtentAlong(d);
    return {std::min(a.lo, b.lo), std::max(a.hi, b.hi)};
  }

 private:
  SphereSurface a_, b_;
};

}  // namespace

std::array<Vec3d, 2> TwoSpheresCentres() {
  const Vec3d half = 0.5 * kTwoSpheresCentreDistance * Normalized({1.0, 1.0, 1.0});
  return {-1.0 * half, half};
}

double CappedSphereMaxZ() { return std::cos(kCapHalfAngleDegrees * std::numbers::pi / 180.0); }

std::unique_ptr<SurfaceSampler> MakeUnitSphere() {
  return std::make_unique<SphereSurface>(Vec3d{0, 0, 0}, 1.0);
}

std::unique_ptr<SurfaceSampler> MakeTwoSpheres() { return std::make_unique<TwoSpheresSurface>(); }

std::unique_ptr<SurfaceSampler> MakeCappedSphere() {
  return std::make_unique<SphereSurface>(Vec3d{0, 0, 0}, 1.0, CappedSphereMaxZ());
}

}  // namespace membrane

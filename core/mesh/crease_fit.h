// Two planes meeting at a crease, fitted to the points near one surface vertex in its frame
// (u, v tangent, h along the vertex normal, in voxels): the fit's target where the data shows a
// sharp edge (issue 17: "sharp edges must stay sharp where the data shows them"). One height
// quadric over points on both sides of a crease bends through it and rounds it by about a
// third of a voxel; the envelope of two planes (the lower one on a ridge, the upper one in a
// valley) follows it, and a vertex placed on the planes' line of intersection puts the mesh's
// edges on the crease, as dual contouring's vertices do.
#ifndef MEMBRANE_CORE_MESH_CREASE_FIT_H_
#define MEMBRANE_CORE_MESH_CREASE_FIT_H_

#include <array>
#include <optional>
#include <vector>

#include "absl/types/span.h"
#include "core/geometry/vec3.h"
#include "core/mesh/height_quadric.h"

namespace membrane {

// One weighted point in a vertex's frame, in voxels.
struct FramePoint {
  double u = 0, v = 0, h = 0;
  double w = 0;  // > 0
};

// When two planes are taken for a crease (and not the quadric). Lengths in voxels.
struct CreaseLimits {
  // The quadric's RMS residual over the points must reach this before two planes are tried:
  // below it the quadric explains the points as well as the voxel can show.
  double min_quadric_rms = 0.04;
  // The two planes' RMS residual (of their envelope) at most this fraction of the quadric's:
  // a crease explains what the quadric leaves; noise on a smooth surface it does not.
  double max_rms_ratio = 0.5;
  // The planes' normals at least this many degrees apart.
  double min_angle_degrees = 25;
  // Each plane holds at least this many points and this share of the weight.
  int min_side_points = 5;
  double min_side_share = 0.15;
  // A vertex whose tangential distance from the crease line is at most this goes onto the
  // line (its nearest point there); one farther moves along its normal to the envelope.
  double snap_distance = 0.5;
  // The points' noise across their surface (point_noise.h), voxels; 0 when unknown. Noise
  // leaves a quadric residual of its own, which no crease explains: two planes are tried only
  // where the quadric's RMS reaches noise_trigger times it, and their envelope's RMS within
  // noise_accept times it counts as explaining the points (if also within max_noisy_ratio of
  // the quadric's) where max_rms_ratio would refuse it.
  double noise = 0;
  double noise_trigger = 1.5;
  double noise_accept = 1.2;
  double max_noisy_ratio = 0.8;
};

// Whether a quadric with this RMS residual (voxels) is to be tried as a crease (FitCrease
// refuses the others anyway: this spares collecting their points).
bool CreaseWorthTrying(double quadric_rms, const CreaseLimits& limits);

struct CreaseFit {
  // h = c[0] + c[1] u + c[2] v for each plane.
  std::array<double, 3> first{}, second{};
  bool ridge = true;      // the surface is the lower of the two planes (else the upper)
  double rms = 0;         // of the envelope over the points, voxels
  bool on_line = false;   // the target lies on the planes' line of intersection
  Vec3d target{0, 0, 0};  // (u, v, h), voxels
};

// Input: the points near a vertex in its frame (the vertex at the origin), `quadric` the
// least-squares height quadric of the same points (its second derivatives give the first
// split, across the direction it bends most) and `quadric_rms` its RMS residual.
// Output: two planes, split by alternately fitting each side's plane and giving each point to
// the nearer one (at most 12 rounds, stopping when no point changes side), and their envelope,
// or nullopt when the limits refuse them (too few points on a side, planes nearly parallel,
// residual not small enough against the quadric's, a singular side). The target is the
// crease line's point nearest the vertex when within `snap_distance` tangentially, else the
// envelope's height above the vertex.
std::optional<CreaseFit> FitCrease(absl::Span<const FramePoint> points,
                                   const HeightQuadric& quadric, double quadric_rms,
                                   const CreaseLimits& limits);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_CREASE_FIT_H_

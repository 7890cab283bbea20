#include "core/engine/thin_wall_faces.h"

#include <algorithm>
#include <array>
#include <optional>

#include "core/geometry/symmetric_eigen3.h"
#include "core/geometry/vec3.h"

namespace membrane {
namespace {

// Radius of the voxels read around an end (the run's hard voxel beside it holds a point within
// 1.8 voxels of its centre), and how much farther than the nearest point a point may lie and
// still count as the face the end sees (under the thinnest wall the test reads, 1 voxel).
constexpr int kFacingRadius = 2;
constexpr double kFacingBand = 0.5;
constexpr double kFacingMaxBand = 1.0;
// Points give a plane when they are this many at least and their scatter across it is under
// this share of the least along it.
constexpr int kPlanePoints = 4;
constexpr double kPlaneRatio = 0.25;

// The normal of the plane of `count` points whose scatter about their mean is `scatter`, into
// `normal`, when they hold a plane (enough points, flat enough); `normal` is left as it is
// otherwise.
void PlaneOf(const SymmetricMatrix3& scatter, double count, Vec3d& normal) {
  if (count < kPlanePoints) return;
  const Eigenvalues3 values = SymmetricEigenvalues(scatter);
  if (!(values.smallest < kPlaneRatio * values.middle)) return;
  if (const std::optional<Vec3d> found = EigenvectorOf(scatter, values.smallest)) normal = *found;
}

}  // namespace

double FacingGap(const VoxelGrid& grid, const HardVoxelPoints& points, const Coord& a,
                 const Coord& b) {
  HardVoxelPoints::Patch pa, pb;
  if (!points.FacingPatch(grid, a, kFacingRadius, kFacingBand, kPlanePoints, kFacingMaxBand,
                          pa) ||
      !points.FacingPatch(grid, b, kFacingRadius, kFacingBand, kPlanePoints, kFacingMaxBand,
                          pb)) {
    return -1;
  }
  const Vec3d ca{a.x + 0.5, a.y + 0.5, a.z + 0.5}, cb{b.x + 0.5, b.y + 0.5, b.z + 0.5};
  const Vec3d ma = pa.mean, mb = pb.mean;
  const Vec3d ta = ca - ma, tb = cb - mb;
  const double la = Norm(ta), lb = Norm(tb);
  if (la < 1e-6 || lb < 1e-6) return -1;
  // The pooled plane of the two patches about their own means (the wall's thickness does not
  // tilt it), where they hold one; else the mean of the two ends' directions to their feet.
  Vec3d common = Normalized((1 / la) * ta - (1 / lb) * tb);
  SymmetricMatrix3 pooled;
  for (int k = 0; k < 6; ++k) pooled[k] = pa.scatter[k] + pb.scatter[k];
  PlaneOf(pooled, pa.count + pb.count, common);
  // Each patch's own plane where it holds one: at a cup's bottom edge one end faces the bottom
  // and the other the corner's two faces, which no one plane holds.
  Vec3d na = common, nb = common;
  PlaneOf(pa.scatter, pa.count, na);
  PlaneOf(pb.scatter, pb.count, nb);
  // An end whose centre lies on its face (in a data gap of a sparse face) has its foot beside
  // it, not below it: the run's own direction, from the other end, orients its normal too.
  const Vec3d run = Normalized(ca - cb);
  if (Dot(na, (1 / la) * ta + run) < 0) na = -1.0 * na;
  if (Dot(nb, (1 / lb) * tb - run) < 0) nb = -1.0 * nb;
  // How far behind one patch's plane the other patch lies, the larger of the two readings: at
  // the bottom's edge the corner's patch fits no plane well and reads low, while the bottom's
  // own patch reads the wall. One sheet seen from both sides has both patches on one plane.
  return std::max(Dot(ma - mb, na), Dot(mb - ma, nb));
}

}  // namespace membrane

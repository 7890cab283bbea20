#include "core/synth/cube_pinholes.h"

#include <algorithm>
#include <cmath>

#include "absl/status/status.h"
#include "absl/strings/str_format.h"
#include "core/synth/synth_random.h"

namespace membrane {
namespace {

// Half-width of the jitter around a voxel centre, in voxels: keeps every point 0.25 l away
// from its voxel's faces.
constexpr double kJitter = 0.25;

// Voxels on the wall of an m^3 cube.
int64_t WallVoxels(int64_t m) { return m * m * m - (m - 2) * (m - 2) * (m - 2); }

// Calls f(c) for every open (non-hole) wall voxel, z slowest, x fastest. Visits only the wall:
// an interior row contributes its two end voxels.
template <typename F>
void ForEachOpenWallVoxel(const CubePinholesGrid& g, F f) {
  const int m = g.side;
  for (int z = 0; z < m; ++z)
    for (int y = 0; y < m; ++y) {
      const bool full_row = z == 0 || y == 0 || z == m - 1 || y == m - 1;
      for (int x = 0; x < m; x += (full_row || x == m - 1) ? 1 : m - 1) {
        const std::array<int, 3> c = {x, y, z};
        if (!g.IsHole(c)) f(c);
      }
    }
}

absl::Status RejectUnsupported(const SynthOptions& o) {
  if (o.holes != 0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "holes = %d is not supported by cube-pinholes: must be 0 (its holes are the two "
        "pinholes, sized by hole_size)",
        o.holes));
  }
  if (o.noise != 0.0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "noise = %g is not supported by cube-pinholes: must be 0 (points must stay in their "
        "voxels)",
        o.noise));
  }
  if (o.density_ratio != 1.0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "density_ratio = %g is not supported by cube-pinholes: must be 1", o.density_ratio));
  }
  return absl::OkStatus();
}

}  // namespace

bool CubePinholesGrid::IsWall(const std::array<int, 3>& c) const {
  for (int v : c)
    if (v == 0 || v == side - 1) return true;
  return false;
}

bool CubePinholesGrid::IsHole(const std::array<int, 3>& c) const {
  const auto in_hole = [&](int v) { return v >= hole_lo && v < hole_lo + hole_size; };
  return (c[0] == 0 || c[0] == side - 1) && in_hole(c[1]) && in_hole(c[2]);
}

absl::StatusOr<CubePinholesGrid> CubePinholesGridFor(const SynthOptions& o) {
  if (absl::Status s = ValidateSynthOptions(o); !s.ok()) return s;
  const int64_t k = o.hole_size;
  CubePinholesGrid g;
  g.hole_size = o.hole_size;
  if (o.voxel_size > 0.0) {
    g.side = std::max(3, static_cast<int>(std::lround(2.0 / o.voxel_size)));
    g.voxel_size = o.voxel_size;
  } else {
    // Grow while the next side still gets kCubePointsPerVoxel per open voxel; m <= 1500 for
    // the largest point count, so the loop is short.
    g.side = 3;
    while (kCubePointsPerVoxel * (WallVoxels(g.side + 1) - 2 * k * k) <= o.points) ++g.side;
    g.voxel_size = 2.0 / g.side;
  }
  if (g.hole_size > g.side - 2) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "hole_size = %d is out of range: must be in [1, %d] for a cube of %d voxels per side",
        g.hole_size, g.side - 2, g.side));
  }
  g.hole_lo = (g.side - g.hole_size) / 2;
  g.open_wall_voxels = WallVoxels(g.side) - 2 * k * k;
  if (o.points < g.open_wall_voxels) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "points = %d is out of range: must be in [%d, %d] for cube-pinholes at voxel_size %g "
        "(%d open wall voxels, each needing a point)",
        o.points, g.open_wall_voxels, kMaxSynthPoints, g.voxel_size, g.open_wall_voxels));
  }
  // A float value, so that the corner point stored as float is exactly the origin.
  const double origin = static_cast<float>(-0.5 * g.side * g.voxel_size);
  g.origin = {origin, origin, origin};
  return g;
}

absl::StatusOr<PointCloud> SynthesizeCubePinholes(const SynthOptions& options) {
  absl::StatusOr<CubePinholesGrid> grid = CubePinholesGridFor(options);
  if (!grid.ok()) return grid.status();
  if (absl::Status s = RejectUnsupported(options); !s.ok()) return s;
  const CubePinholesGrid& g = *grid;
  std::mt19937_64 rng = SeededStream(options.seed, kSampleStream);
  const double l = g.voxel_size;
  const int64_t base = options.points / g.open_wall_voxels;
  int64_t extra_left = options.points % g.open_wall_voxels;
  int64_t voxels_left = g.open_wall_voxels;

  PointCloud cloud;
  cloud.points.reserve(static_cast<size_t>(options.points));
  const auto push = [&](const std::array<int, 3>& c, double dx, double dy, double dz) {
    cloud.points.push_back({static_cast<float>(g.origin[0] + (c[0] + dx) * l),
                            static_cast<float>(g.origin[1] + (c[1] + dy) * l),
                            static_cast<float>(g.origin[2] + (c[2] + dz) * l)});
  };
  ForEachOpenWallVoxel(g, [&](const std::array<int, 3>& c) {
    // Selection sampling (Knuth's algorithm S): exactly extra_left of the remaining voxels get
    // one more point, each equally likely, without storing the voxel list.
    int64_t count = base;
    if (extra_left > 0 && Uniform01(rng) * static_cast<double>(voxels_left) <
                              static_cast<double>(extra_left)) {
      ++count;
      --extra_left;
    }
    --voxels_left;
    const bool anchor = c[0] == 0 && c[1] == 0 && c[2] == 0;
    if (anchor) {
      push(c, 0.0, 0.0, 0.0);  // pins the bounding-box min to the grid origin
    } else {
      push(c, 0.5, 0.5, 0.5);  // the far corner's centre pins the bounding-box max
    }
    for (int64_t i = 1; i < count; ++i) {
      const double dx = 0.5 + kJitter * (2.0 * Uniform01(rng) - 1.0);
      const double dy = 0.5 + kJitter * (2.0 * Uniform01(rng) - 1.0);
      const double dz = 0.5 + kJitter * (2.0 * Uniform01(rng) - 1.0);
      push(c, dx, dy, dz);
    }
  });
  return cloud;
}

}  // namespace membrane

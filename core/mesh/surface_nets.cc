#include "core/mesh/surface_nets.h"

#include <vector>

#include "core/mesh/crossing_repair.h"
#include "core/mesh/morton_order.h"
#include "core/mesh/polygon_split.h"
#include "core/mesh/voxel_boundary.h"

namespace membrane {
namespace {

// How far a midpoint vertex sits from the middle of its two ends, toward the outside voxel
// centre its quad pair wraps around, as a fraction of the distance from the ambiguous face's
// centre to that voxel centre: it keeps the two pairs' new edges apart.
constexpr double kMidpointPull = 0.5;
// The fallback geometry (see SurfaceNets): offsets in voxels from the lattice corner / edge
// midpoint, as in the cuberille.
constexpr double kSafeSplitOffset = 0.2;
constexpr double kSafeMidpointOffset = 0.2;
constexpr double kSafeCornerRetreat = 0.25;

Vec3d OctantDirection(int octant) {
  return {(octant & 1) ? 1.0 : -1.0, (octant & 2) ? 1.0 : -1.0, (octant & 4) ? 1.0 : -1.0};
}

// Lattice-unit positions: the surface nets (`nets`) and the embedded fallback (`safe`).
struct Placement {
  std::vector<Vec3d> nets, safe;
};

Placement Place(const VoxelBoundary& b) {
  Placement p;
  p.nets.reserve(b.num_vertices());
  p.safe.reserve(b.num_vertices());
  for (const auto& v : b.fan_vertices) {
    const Vec3d corner = LatticePosition(v.corner);
    p.nets.push_back(corner + FanCentroid(v.config, v.fan));
    Vec3d safe = corner;
    if (IsCornerContact(v.config)) {
      // Each of the two cubes pulls its corner in: the sheets part instead of touching.
      safe = corner +
             kSafeCornerRetreat * Normalized(OctantDirection(FanSolidOctant(v.config, v.fan)));
    } else if (NumFans(v.config) > 1) {
      safe = corner + kSafeSplitOffset * Normalized(FanOutsideDirection(v.config, v.fan));
    }
    p.safe.push_back(safe);
  }
  for (const auto& m : b.midpoints) {
    Vec3d face_centre = LatticePosition(m.edge_start);
    face_centre[m.axis] += 0.5;
    const Vec3d outside_centre = LatticePosition(m.outside) + Vec3d{0.5, 0.5, 0.5};
    p.nets.push_back(0.5 * (p.nets[m.ends[0]] + p.nets[m.ends[1]]) +
                     kMidpointPull * (outside_centre - face_centre));
    p.safe.push_back(face_centre + kSafeMidpointOffset * Normalized(outside_centre - face_centre));
  }
  return p;
}

std::vector<Point3f> ToModel(const VoxelGrid& grid, const std::vector<Vec3d>& lattice) {
  const double l = grid.voxel_size();
  const auto& o = grid.origin();
  std::vector<Point3f> out;
  out.reserve(lattice.size());
  for (const Vec3d& v : lattice)
    out.push_back(ToPoint3f({o[0] + v[0] * l, o[1] + v[1] * l, o[2] + v[2] * l}));
  return out;
}

}  // namespace

UnrepairedSurfaceNets SurfaceNetsBeforeRepair(const VoxelGrid& grid, int threads) {
  const VoxelBoundary b = ExtractVoxelBoundary(grid, threads);
  const Placement p = Place(b);
  TriangleMesh mesh;
  mesh.faces.reserve(2 * b.quads.size());
  std::vector<int32_t> polygon;
  for (const auto& quad : b.quads) {
    polygon.clear();
    int apex = -1;
    for (int k = 0; k < 4; ++k) {
      polygon.push_back(quad.corners[k]);
      if (quad.midpoints[k] >= 0) {
        if (apex < 0) apex = static_cast<int>(polygon.size());
        polygon.push_back(quad.midpoints[k]);
      }
    }
    if (apex < 0) {
      SplitQuadFlatter(quad.corners, p.nets, mesh.faces);
    } else {
      SplitPolygonFan(polygon, apex, mesh.faces);
    }
  }
  mesh.vertices = ToModel(grid, p.nets);
  // Spatial order for everything downstream; the fallback positions travel with their
  // vertices.
  UnrepairedSurfaceNets out{std::move(mesh), ToModel(grid, p.safe), b.corner_contacts};
  MortonOrder(out.mesh, grid.voxel_size(), &out.fallback, threads);
  return out;
}

TriangleMesh SurfaceNets(const VoxelGrid& grid, SurfaceNetsStats* stats) {
  UnrepairedSurfaceNets nets = SurfaceNetsBeforeRepair(grid);
  const CrossingRepair repair = RepairCrossings(nets.mesh, nets.fallback);
  if (stats) {
    stats->corner_contacts = nets.corner_contacts;
    stats->repaired_vertices = repair.moved_vertices;
    stats->crossings_left = repair.crossings_left;
  }
  return std::move(nets.mesh);
}

}  // namespace membrane

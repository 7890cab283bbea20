#include "core/mesh/surface_nets.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/base/parallel_tasks.h"
#include "core/engine/arena_allocator.h"
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

// Lattice-unit positions: the surface nets (`nets`) and the embedded fallback (`safe`). Left
// unset when made: the ranges on the threads write them first (their page faults included).
using Positions = std::vector<Vec3d, UnfilledAllocator<Vec3d>>;
struct Placement {
  Positions nets, safe;
};

// Ranges of `n` items for `threads` threads: 4 a thread (the ranges' costs vary little), or one
// range below kMinRangeItems items.
constexpr int64_t kMinRangeItems = int64_t{1} << 16;
int64_t NumRanges(int64_t n, int threads) {
  return threads > 1 && n >= kMinRangeItems ? 4 * int64_t{threads} : 1;
}
// Calls body(begin, end) for `ranges` equal ranges of [0, n) on the threads.
template <typename Body>
void ForRanges(int threads, int64_t n, int64_t ranges, Body body) {
  RunTasks(threads, ranges, [&](int, int64_t r) { body(r * n / ranges, (r + 1) * n / ranges); });
}

Placement Place(const VoxelBoundary& b, int threads) {
  Placement p;
  const int64_t nfan = static_cast<int64_t>(b.fan_vertices.size());
  const int64_t nmid = static_cast<int64_t>(b.midpoints.size());
  p.nets.resize(static_cast<size_t>(nfan + nmid));
  p.safe.resize(static_cast<size_t>(nfan + nmid));
  ForRanges(threads, nfan, NumRanges(nfan, threads), [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      const auto& v = b.fan_vertices[static_cast<size_t>(i)];
      const Vec3d corner = LatticePosition(v.corner);
      p.nets[i] = corner + FanCentroid(v.config, v.fan);
      Vec3d safe = corner;
      if (IsCornerContact(v.config)) {
        // Each of the two cubes pulls its corner in: the sheets part instead of touching.
        safe = corner +
               kSafeCornerRetreat * Normalized(OctantDirection(FanSolidOctant(v.config, v.fan)));
      } else if (NumFans(v.config) > 1) {
        safe = corner + kSafeSplitOffset * Normalized(FanOutsideDirection(v.config, v.fan));
      }
      p.safe[i] = safe;
    }
  });
  // Midpoints after the fan vertices: each sits between two of them.
  ForRanges(threads, nmid, NumRanges(nmid, threads), [&](int64_t begin, int64_t end) {
    for (int64_t j = begin; j < end; ++j) {
      const auto& m = b.midpoints[static_cast<size_t>(j)];
      Vec3d face_centre = LatticePosition(m.edge_start);
      face_centre[m.axis] += 0.5;
      const Vec3d outside_centre = LatticePosition(m.outside) + Vec3d{0.5, 0.5, 0.5};
      p.nets[nfan + j] = 0.5 * (p.nets[m.ends[0]] + p.nets[m.ends[1]]) +
                         kMidpointPull * (outside_centre - face_centre);
      p.safe[nfan + j] =
          face_centre + kSafeMidpointOffset * Normalized(outside_centre - face_centre);
    }
  });
  return p;
}

std::vector<Point3f> ToModel(const VoxelGrid& grid, const Positions& lattice,
                             int threads) {
  const double l = grid.voxel_size();
  const auto& o = grid.origin();
  const int64_t n = static_cast<int64_t>(lattice.size());
  std::vector<Point3f> out(lattice.size());
  ForRanges(threads, n, NumRanges(n, threads), [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      const Vec3d& v = lattice[i];
      out[i] = ToPoint3f({o[0] + v[0] * l, o[1] + v[1] * l, o[2] + v[2] * l});
    }
  });
  return out;
}

// The triangles of each quad in quad order: two for a plain quad, split along its flatter
// diagonal; a fan from the first midpoint for a quad with midpoints. Ranges of quads on the
// threads, each writing where the triangles before it end.
std::vector<std::array<int32_t, 3>> Triangulate(const VoxelBoundary& b,
                                                const Positions& nets, int threads) {
  const int64_t nquads = static_cast<int64_t>(b.quads.size());
  const int64_t ranges = NumRanges(nquads, threads);
  auto range_of = [&](int64_t r) {
    return std::pair<int64_t, int64_t>{r * nquads / ranges, (r + 1) * nquads / ranges};
  };
  std::vector<int64_t> first(static_cast<size_t>(ranges + 1), 0);
  RunTasks(threads, ranges, [&](int, int64_t r) {
    const auto [begin, end] = range_of(r);
    int64_t count = 0;
    for (int64_t q = begin; q < end; ++q) {
      count += 2;
      for (int32_t m : b.quads[static_cast<size_t>(q)].midpoints) count += m >= 0 ? 1 : 0;
    }
    first[static_cast<size_t>(r) + 1] = count;
  });
  for (int64_t r = 0; r < ranges; ++r) first[r + 1] += first[r];
  std::vector<std::array<int32_t, 3>> faces(static_cast<size_t>(first[ranges]));
  RunTasks(threads, ranges, [&](int, int64_t r) {
    const auto [begin, end] = range_of(r);
    auto at = faces.begin() + first[r];
    std::vector<int32_t> polygon;
    std::vector<std::array<int32_t, 3>> triangles;
    for (int64_t q = begin; q < end; ++q) {
      const auto& quad = b.quads[static_cast<size_t>(q)];
      polygon.clear();
      triangles.clear();
      int apex = -1;
      for (int k = 0; k < 4; ++k) {
        polygon.push_back(quad.corners[k]);
        if (quad.midpoints[k] >= 0) {
          if (apex < 0) apex = static_cast<int>(polygon.size());
          polygon.push_back(quad.midpoints[k]);
        }
      }
      if (apex < 0) {
        SplitQuadFlatter(quad.corners, nets.data(), triangles);
      } else {
        SplitPolygonFan(polygon, apex, triangles);
      }
      at = std::copy(triangles.begin(), triangles.end(), at);
    }
  });
  return faces;
}

}  // namespace

UnrepairedSurfaceNets SurfaceNetsBeforeRepair(const VoxelGrid& grid, int threads) {
  const VoxelBoundary b = ExtractVoxelBoundary(grid, threads);
  const Placement p = Place(b, threads);
  TriangleMesh mesh;
  mesh.faces = Triangulate(b, p.nets, threads);
  mesh.vertices = ToModel(grid, p.nets, threads);
  // Spatial order for everything downstream; the fallback positions travel with their
  // vertices.
  UnrepairedSurfaceNets out{std::move(mesh), ToModel(grid, p.safe, threads), b.corner_contacts};
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

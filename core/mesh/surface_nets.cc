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

// Writes the model positions of `lattice` into `out`, sized to match.
void ToModel(const VoxelGrid& grid, const Positions& lattice, int threads,
             std::vector<Point3f>& out) {
  const double l = grid.voxel_size();
  const auto& o = grid.origin();
  const int64_t n = static_cast<int64_t>(lattice.size());
  ForRanges(threads, n, NumRanges(n, threads), [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      const Vec3d& v = lattice[i];
      out[i] = ToPoint3f({o[0] + v[0] * l, o[1] + v[1] * l, o[2] + v[2] * l});
    }
  });
}

// The quads' ranges for the triangulation and where each range's triangles start: two for a
// plain quad, one more for each midpoint; first.back() is the triangle count.
struct QuadRanges {
  int64_t ranges = 1;
  std::vector<int64_t> first;
};

QuadRanges CountTriangles(const VoxelBoundary& b, int threads) {
  const int64_t nquads = static_cast<int64_t>(b.quads.size());
  QuadRanges q;
  q.ranges = NumRanges(nquads, threads);
  q.first.assign(static_cast<size_t>(q.ranges + 1), 0);
  RunTasks(threads, q.ranges, [&](int, int64_t r) {
    int64_t count = 0;
    for (int64_t i = r * nquads / q.ranges; i < (r + 1) * nquads / q.ranges; ++i) {
      count += 2;
      for (int32_t m : b.quads[static_cast<size_t>(i)].midpoints) count += m >= 0 ? 1 : 0;
    }
    q.first[static_cast<size_t>(r) + 1] = count;
  });
  for (int64_t r = 0; r < q.ranges; ++r) q.first[r + 1] += q.first[r];
  return q;
}

// Writes the triangles of each quad into `faces` (sized to the count) in quad order: two for a
// plain quad, split along its flatter diagonal; a fan from the first midpoint for a quad with
// midpoints. Ranges of quads on the threads, each writing where the triangles before it end.
void Triangulate(const VoxelBoundary& b, const Positions& nets, const QuadRanges& q,
                 int threads, std::vector<std::array<int32_t, 3>>& faces) {
  const int64_t nquads = static_cast<int64_t>(b.quads.size());
  RunTasks(threads, q.ranges, [&](int, int64_t r) {
    const int64_t begin = r * nquads / q.ranges, end = (r + 1) * nquads / q.ranges;
    auto at = faces.begin() + q.first[static_cast<size_t>(r)];
    std::vector<int32_t> polygon;
    std::vector<std::array<int32_t, 3>> triangles;
    for (int64_t i = begin; i < end; ++i) {
      const auto& quad = b.quads[static_cast<size_t>(i)];
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
}

}  // namespace

UnrepairedSurfaceNets SurfaceNetsBeforeRepair(const VoxelGrid& grid, int threads) {
  const VoxelBoundary b = ExtractVoxelBoundary(grid, threads);
  const Placement p = Place(b, threads);
  const QuadRanges quads = CountTriangles(b, threads);
  UnrepairedSurfaceNets out;
  out.corner_contacts = b.corner_contacts;
  // The mesh's arrays are std::vectors, zeroed when sized: the faces on one thread and the two
  // position arrays on another (about as many bytes), so that their first writes, the fresh
  // pages' faults, are split; the ranges then write them.
  const size_t nv = p.nets.size();
  RunTasks(threads, 2, [&](int, int64_t task) {
    if (task == 0) {
      out.mesh.faces.resize(static_cast<size_t>(quads.first.back()));
    } else {
      out.mesh.vertices.resize(nv);
      out.fallback.resize(nv);
    }
  });
  Triangulate(b, p.nets, quads, threads, out.mesh.faces);
  ToModel(grid, p.nets, threads, out.mesh.vertices);
  // The fallback positions travel with their vertices.
  ToModel(grid, p.safe, threads, out.fallback);
  // Spatial order for everything downstream.
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

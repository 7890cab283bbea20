#include "core/mesh/cuberille.h"

#include <cstdint>
#include <utility>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "core/mesh/polygon_split.h"
#include "core/mesh/voxel_boundary.h"

namespace membrane {
namespace {

// Offsets in voxels. Small enough that split copies of one corner stay in their own octants
// (< 0.5) and chamfer points of the two ends of an edge never meet (< 0.5), large enough to
// survive float32 rounding at any sensible grid size.
constexpr double kSplitOffset = 0.2;
constexpr double kMidpointOffset = 0.2;
constexpr double kChamfer = 0.25;

// Vertices in lattice units; chamfer points are appended after the boundary's vertex ids.
class CuberilleBuilder {
 public:
  explicit CuberilleBuilder(const VoxelBoundary& b) : b_(b) {
    positions_.reserve(b.num_vertices());
    triangles_.reserve(2 * b.quads.size());  // plain quads; split ones add a few more
    for (const auto& v : b.fan_vertices) {
      Vec3d p = LatticePosition(v.corner);
      if (NumFans(v.config) > 1 && !IsCornerContact(v.config))
        p = p + kSplitOffset * Normalized(FanOutsideDirection(v.config, v.fan));
      positions_.push_back(p);
    }
    for (const auto& m : b.midpoints) {
      Vec3d mid = LatticePosition(m.edge_start);
      mid[m.axis] += 0.5;
      const Vec3d centre = LatticePosition(m.outside) + Vec3d{0.5, 0.5, 0.5};
      positions_.push_back(mid + kMidpointOffset * Normalized(centre - mid));
    }
  }

  TriangleMesh Build(const VoxelGrid& grid) {
    std::vector<int32_t> polygon;
    for (const auto& quad : b_.quads) {
      const std::array<Coord, 4> corner = QuadCornerCoords(quad);
      polygon.clear();
      int apex = -1;
      bool plain = true;
      for (int k = 0; k < 4; ++k) {
        const int32_t v = quad.corners[k];
        const auto& fv = b_.fan_vertices[v];
        if (IsCornerContact(fv.config)) {
          plain = false;
          polygon.push_back(Chamfer(v, corner[k], corner[(k + 3) % 4]));
          polygon.push_back(Chamfer(v, corner[k], corner[(k + 1) % 4]));
        } else {
          polygon.push_back(v);
        }
        if (quad.midpoints[k] >= 0) {
          plain = false;
          if (apex < 0) apex = static_cast<int>(polygon.size());
          polygon.push_back(quad.midpoints[k]);
        }
      }
      if (plain) {
        SplitQuadFlatter({polygon[0], polygon[1], polygon[2], polygon[3]}, positions_.data(),
                         triangles_);
      } else {
        SplitPolygonFan(polygon, apex < 0 ? 0 : apex, triangles_);
      }
    }
    AddCornerTubes();
    return Compact(grid);
  }

 private:
  // The chamfer point of fan vertex `v` (at lattice corner `corner`) on the edge toward
  // `toward`.
  int32_t Chamfer(int32_t v, const Coord& corner, const Coord& toward) {
    int axis = 0;
    while (corner[axis] == toward[axis]) ++axis;
    const int sign = toward[axis] > corner[axis] ? 1 : -1;
    auto [it, inserted] = chamfers_.try_emplace(std::pair<int32_t, int>{v, axis});
    if (inserted) {
      Vec3d p = LatticePosition(corner);
      p[axis] += sign * kChamfer;
      it->second = static_cast<int32_t>(positions_.size());
      positions_.push_back(p);
    }
    return it->second;
  }

  // Joins the two cut-back corners of each corner contact by the 6 faces of the octahedron
  // around the corner that are neither cut-back triangle: a tube lying in the 6 outside octants.
  void AddCornerTubes() {
    for (size_t i = 0; i < b_.fan_vertices.size(); ++i) {
      const auto& fv = b_.fan_vertices[i];
      if (!IsCornerContact(fv.config) || fv.fan != 0) continue;
      const int32_t va = static_cast<int32_t>(i), vb = va + 1;  // the corner's two fans
      const int octant = FanSolidOctant(fv.config, 0);
      const Vec3d centre = LatticePosition(fv.corner);
      std::array<int32_t, 3> a, b;
      for (int axis = 0; axis < 3; ++axis) {
        Coord toward_a = fv.corner, toward_b = fv.corner;
        const int sign = ((octant >> axis) & 1) ? 1 : -1;
        toward_a[axis] += sign;
        toward_b[axis] -= sign;
        a[axis] = Chamfer(va, fv.corner, toward_a);
        b[axis] = Chamfer(vb, fv.corner, toward_b);
      }
      for (int pattern = 1; pattern < 7; ++pattern) {
        std::array<int32_t, 3> t;
        for (int axis = 0; axis < 3; ++axis) t[axis] = ((pattern >> axis) & 1) ? a[axis] : b[axis];
        const Vec3d n = TriangleNormal(positions_[t[0]], positions_[t[1]], positions_[t[2]]);
        if (Dot(n, positions_[t[0]] - centre) < 0) std::swap(t[1], t[2]);
        triangles_.push_back(t);
      }
    }
  }

  // Drops vertices no triangle uses (fan vertices replaced by chamfer points) and converts
  // lattice units to model units.
  TriangleMesh Compact(const VoxelGrid& grid) {
    TriangleMesh mesh;
    mesh.vertices.reserve(positions_.size());
    std::vector<int32_t> remap(positions_.size(), -1);
    const double l = grid.voxel_size();
    const auto& o = grid.origin();
    for (auto& t : triangles_) {
      for (int32_t& v : t) {
        if (remap[v] < 0) {
          remap[v] = static_cast<int32_t>(mesh.vertices.size());
          const Vec3d& p = positions_[v];
          mesh.vertices.push_back(ToPoint3f({o[0] + p[0] * l, o[1] + p[1] * l, o[2] + p[2] * l}));
        }
        v = remap[v];
      }
    }
    mesh.faces = std::move(triangles_);
    return mesh;
  }

  const VoxelBoundary& b_;
  std::vector<Vec3d> positions_;
  std::vector<std::array<int32_t, 3>> triangles_;
  absl::flat_hash_map<std::pair<int32_t, int>, int32_t> chamfers_;
};

}  // namespace

TriangleMesh Cuberille(const VoxelGrid& membrane) {
  const VoxelBoundary boundary = ExtractVoxelBoundary(membrane);
  return CuberilleBuilder(boundary).Build(membrane);
}

}  // namespace membrane

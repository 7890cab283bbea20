// Per-vertex lists of the input points near a surface vertex, kept across the fit's rounds
// (point_fitting.h). A vertex moves a fraction of a voxel between rounds, so one list gathered
// with a margin serves every later query centred within that margin of where it was gathered:
// a query then scans a few dozen listed points instead of the grid cells' hundred or more.
#ifndef MEMBRANE_CORE_MESH_NEAR_POINT_CACHE_H_
#define MEMBRANE_CORE_MESH_NEAR_POINT_CACHE_H_

#include <cstdint>
#include <vector>

#include "core/mesh/point_hash_grid.h"
#include "core/mesh/vec3.h"

namespace membrane {

class NearPointCache {
 public:
  // `grid` must outlive the cache; `radius` > 0 the query radius and `margin` >= 0 how far a
  // query centre may stray from where its vertex's list was gathered (model units).
  NearPointCache(const PointHashGrid& grid, int32_t num_vertices, double radius, double margin);

  // Calls fn(const Point3f&, double squared_distance) for every point of the grid within the
  // radius of `centre`, on behalf of vertex `v`: exactly the points and the order of
  // grid.ForEachWithin(centre, radius, fn), with the same squared distances, so the caller's
  // sums are bit for bit those of a grid query. The first query of `v`, and any centred more
  // than the margin away from where v's list was gathered, gathers a new list (radius plus
  // margin) from the grid.
  template <typename Fn>
  void ForEachWithin(int32_t v, const Vec3d& centre, Fn fn) {
    if (!Fresh(v, centre)) Gather(v, centre);
    const double r2 = radius_ * radius_;
    const uint32_t* it = pool_.data() + begin_[v];
    const uint32_t* const end = it + count_[v];
    for (; it != end; ++it) {
      const Point3f& p = grid_.point(*it);
      // The grid's own arithmetic, so that the same points pass with the same distances.
      const double dx = p[0] - centre[0], dy = p[1] - centre[1], dz = p[2] - centre[2];
      const double d2 = dx * dx + dy * dy + dz * dz;
      if (d2 <= r2) fn(p, d2);
    }
  }

  // Lists gathered so far (one per vertex queried, plus one per stray beyond the margin).
  int64_t gathers() const { return gathers_; }

 private:
  bool Fresh(int32_t v, const Vec3d& centre) const {
    return count_[v] != kNone && SquaredNorm(centre - centre_[v]) <= margin_ * margin_;
  }
  void Gather(int32_t v, const Vec3d& centre);

  static constexpr uint32_t kNone = ~uint32_t{0};
  const PointHashGrid& grid_;
  const double radius_, margin_;
  // Lists live back to back in pool_; a re-gathered list is appended (strays are rare).
  std::vector<uint32_t> pool_;
  std::vector<size_t> begin_;
  std::vector<uint32_t> count_;
  std::vector<Vec3d> centre_;
  int64_t gathers_ = 0;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_NEAR_POINT_CACHE_H_

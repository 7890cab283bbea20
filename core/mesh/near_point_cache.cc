#include "core/mesh/near_point_cache.h"

namespace membrane {

NearPointCache::NearPointCache(const PointHashGrid& grid, int32_t num_vertices, double radius,
                               double margin)
    : grid_(grid),
      radius_(radius),
      margin_(margin),
      begin_(num_vertices, 0),
      count_(num_vertices, kNone),
      centre_(num_vertices) {}

void NearPointCache::Gather(int32_t v, const Vec3d& centre) {
  // A point within the radius of a centre within the margin is within radius + margin of the
  // gathering centre; the relative slack covers the rounding of the two distance tests.
  const size_t begin = pool_.size();
  grid_.IndicesWithin(centre, (radius_ + margin_) * (1 + 1e-9), pool_);
  begin_[v] = begin;
  count_[v] = static_cast<uint32_t>(pool_.size() - begin);
  centre_[v] = centre;
  ++gathers_;
}

}  // namespace membrane

#include "core/engine/work_planes.h"

#include "core/engine/interior_plane.h"

namespace membrane {

bool WorkPlanes::Ensure(int count, const CancelToken* cancel) {
  const int64_t nv = grid_.size();
  if (interior_.bits() != nv) interior_ = InteriorPlane(grid_);
  while (static_cast<int>(planes_.size()) < count) {
    // Fresh pages are slow enough that twenty planes of a large grid take longer than a
    // cancel may wait.
    if (cancel != nullptr && cancel->cancelled()) return false;
    planes_.push_back(std::make_unique<FlatBitset>(nv));
  }
  return true;
}

}  // namespace membrane

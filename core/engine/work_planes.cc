#include "core/engine/work_planes.h"

namespace membrane {

bool WorkPlanes::Ensure(int count, const CancelToken& cancel) {
  const int64_t nv = grid_.size();
  if (arena_ == nullptr && count > 0) {
    // Planes are whole words, each block rounded to the arena's block alignment.
    const size_t words = static_cast<size_t>((nv + 63) / 64);
    const size_t block = (words * sizeof(uint64_t) + PlaneArena::kBlockAlignment - 1) /
                         PlaneArena::kBlockAlignment * PlaneArena::kBlockAlignment;
    arena_ = std::make_unique<PlaneArena>(block * kArenaPlanes);
  }
  while (static_cast<int>(planes_.size()) < count) {
    // Fresh pages are slow enough that twenty planes of a large grid take longer than a
    // cancel may wait.
    if (cancel.cancelled()) return false;
    // Zeroed on the planes' threads: these are the planes' first writes, and on a large grid
    // their page faults were a tenth of the calling thread's time in a 2-thread run.
    planes_.push_back(std::make_unique<FlatBitset>(nv, arena_.get(), FlatBitset::Unset{}));
    planes_.back()->set_threads(threads_);
    planes_.back()->set_halo_store(&halo_);
    planes_.back()->clear_all();
  }
  return true;
}

void WorkPlanes::Release() {
  planes_.clear();  // before the arena they were cut from
  arena_.reset();
  std::vector<uint64_t>().swap(halo_);
}

}  // namespace membrane

// A copy of a grid's voxel states held as runs of equal bytes.
//
// The handle retry keeps the grid as it was before a generation, and the finished grid while
// the retry runs; the pipeline keeps the final membrane while the surface cleans and frees
// the grid itself (a second surface starts from the copy). By then the grid is long runs of
// one outside label and of inside voxels, broken only near the membrane: a 10M-point torus's
// 2.2e9 voxel states take about a hundredth of their size as runs, where a plain copy would
// add 2.2 GB per checkpoint beside the grid at the shrink's peak.
#ifndef MEMBRANE_CORE_ENGINE_COMPACT_STATES_H_
#define MEMBRANE_CORE_ENGINE_COMPACT_STATES_H_

#include <cstdint>
#include <vector>

#include "absl/types/span.h"
#include "core/base/cancel_token.h"
#include "core/engine/flat_bitset.h"
#include "core/engine/voxel_state.h"

namespace membrane {

class CompactStates {
 public:
  // Voxels per chunk: chunks are encoded one at a time, as runs or (when runs would take more
  // room than the bytes) as the bytes themselves.
  static constexpr int64_t kChunk = int64_t{1} << 16;

  // Makes this a copy of `states`, reusing its buffers. Polls `cancel` between slices of
  // 16 MB: false when it fired (this is then unusable until the next successful Encode).
  // Runs on `threads` (>= 1), a range of chunks a task, each range's runs and bytes then
  // joined in order: the same copy for any thread count.
  bool Encode(absl::Span<const VoxelState> states, const CancelToken& cancel, int threads = 1);

  // Writes the copy into `states`, which must have size() elements. Polls `cancel` as Encode
  // does: false when it fired (`states` is then partly written). Runs on `threads` (>= 1), a
  // range of chunks a task.
  bool Decode(absl::Span<VoxelState> states, const CancelToken& cancel, int threads = 1) const;

  // `plane` becomes size() bits, bit i set when voxel i of the copy is outside. A plane of
  // that size already keeps its words (a work plane stays in its arena).
  void OutsidePlane(FlatBitset& plane) const;

  // Number of voxels copied.
  int64_t size() const { return size_; }
  // Bytes the copy holds (runs, raw chunks and the chunk table), for tests and reports.
  int64_t encoded_bytes() const;

 private:
  struct Chunk {
    int64_t begin = 0;  // into runs_ (a run chunk) or raw_ (a raw chunk)
    int32_t count = 0;  // runs, or bytes
    bool raw = false;
  };
  // A run: the state in the low 8 bits, the length (1 .. kChunk) above them.
  static uint32_t MakeRun(VoxelState s, int64_t length) {
    return static_cast<uint32_t>(length) << 8 | s;
  }
  static VoxelState RunState(uint32_t run) { return static_cast<VoxelState>(run & 0xff); }
  static int64_t RunLength(uint32_t run) { return run >> 8; }

  void EncodeChunk(const VoxelState* s, int64_t count);
  // Encodes chunks [first, end) of `states` after those already held; false when `cancel`
  // fired.
  bool EncodeChunks(absl::Span<const VoxelState> states, int64_t first, int64_t end,
                    const CancelToken& cancel);

  int64_t size_ = 0;
  std::vector<Chunk> chunks_;
  std::vector<uint32_t> runs_;
  std::vector<VoxelState> raw_;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_COMPACT_STATES_H_

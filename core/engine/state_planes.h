// Bit-planes and counts of voxel-state predicates, eight voxels per step.
//
// The place finder and the closed form rebuild planes such as OUT (outside) and BS (boundary
// soft) from the state bytes of the whole grid several times per generation; bit by bit that
// cost as much as all their word operations together. Here eight state bytes are tested as one
// 64-bit word (the predicate lands in each byte's top bit) and the eight results are packed
// with one multiplication.
#ifndef MEMBRANE_CORE_ENGINE_STATE_PLANES_H_
#define MEMBRANE_CORE_ENGINE_STATE_PLANES_H_

#include <cstdint>

#include "absl/types/span.h"
#include "core/engine/flat_bitset.h"
#include "core/engine/voxel_state.h"

namespace membrane {

enum class StatePredicate {
  kOutside,       // IsOutside
  kBoundarySoft,  // IsBoundarySoft: boundary, soft, not frozen
  kFree,          // !IsHardOrFrozen: a cell a plate may cover
  kHard,          // IsHard
};

// Sets bit i of `plane` to predicate(states[i]) for every i in words [word_begin, word_end)
// of `plane` (bits past states.size() become 0). `plane` must have states.size() bits and
// 0 <= word_begin <= word_end <= plane.word_count(); other words are left as they are.
void FillStatePlane(absl::Span<const VoxelState> states, StatePredicate predicate,
                    FlatBitset& plane, int64_t word_begin, int64_t word_end);

// The same over the whole plane, in blocks of words on plane.threads() threads.
void FillStatePlane(absl::Span<const VoxelState> states, StatePredicate predicate,
                    FlatBitset& plane);

// Sets bit i of `free_cells` to "boundary soft or outside" (the cells a plate may cover, the
// place finder's free plane before its border is cleared) and bit i of `outside` to
// IsOutside(states[i]), reading each state once: the two planes FillStatePlane gives for
// kBoundarySoft or'ed with kOutside, and for kOutside. Both must have states.size() bits and be
// different bitsets; the words run in blocks on free_cells.threads() threads.
void FillFreeAndOutsidePlanes(absl::Span<const VoxelState> states, FlatBitset& free_cells,
                              FlatBitset& outside);

struct StateCounts {
  int64_t outside = 0;
  int64_t boundary = 0;       // IsBoundary, any hardness
  int64_t boundary_soft = 0;  // boundary, soft, not frozen
};

// Counts the outside, boundary and boundary soft voxels of `states` in one pass, in fixed
// blocks of voxels on `threads` threads (the counts do not depend on it).
StateCounts CountStates(absl::Span<const VoxelState> states, int threads = 1);

// Index (0..7) of the first of the eight states at `states` that is a boundary voxel
// (IsBoundary), or 8 when none is: lets a scan for boundary voxels skip eight at a time.
int FirstBoundaryOfEight(const VoxelState* states);

// Index of the first hard state (IsHard) among states[0, count), or count when none is: a
// scan for a grid's few hard voxels reads sixty-four states a step where none is.
int64_t FirstHardOf(const VoxelState* states, int64_t count);

// The top bit of byte k (k < 8) set when states[k] is outside and one of its six face
// neighbours is not (an outside voxel beside the solid), the others clear. `strides` are the
// grid's (1, nx, nx * ny); the face neighbours of all eight must lie in the array.
uint64_t OutsideBesideSolidOfEight(const VoxelState* states, const int64_t strides[3]);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_STATE_PLANES_H_

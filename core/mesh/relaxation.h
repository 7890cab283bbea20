// Discrete membrane relaxation (paper section 5; algorithm-notes decisions 9, 10 and 12).
//
// The discrete local curvature of a boundary voxel V is DLC(V) = #outside - #inside among its
// 26 neighbours, in [-26, 26] (decision 9: the paper's [-25, 25] misses the boundary voxel with
// 26 outside neighbours). Phase 1 takes the movable boundary voxels with DLC <= -13, most
// negative first: V becomes inside and its outside 26-neighbours become (soft) boundary voxels,
// filling a dent. Phase 2 is the mirror image for DLC >= 13, most positive first: V becomes
// outside and its inside 26-neighbours become boundary voxels, shaving a bump. After each step
// the DLC of the voxels around it (the 124-neighbourhood of V) is updated incrementally, and
// those that now qualify are queued. The DLC is summed from the states when it is asked for,
// and only boundary voxels are ever asked: the cost follows the membrane, not the grid (one
// read of the grid for the first qualifying voxels).
//
// Rules beyond the paper:
//   - Movable means boundary, soft OR FROZEN (decision 10: by Property 3 every soft voxel that
//     touches the outside is frozen, so leaving frozen voxels alone moves nothing), never hard,
//     and never on the array's outer 2 padding layers (phase 1 also refuses V when one of its
//     outside neighbours lies there).
//   - Only simple voxels enter or leave the solid (the (26,6) test of local_topology.h, decision
//     12): in phase 1 each outside neighbour is added only if simple at that moment (if one is
//     not, the step is undone and V stays); in phase 2 V leaves only if simple. So the number of
//     shells and the genus never change, and a two-sided sheet (decision 10: it scores about
//     +18) is never deleted, since removing one of its voxels would join the outside on its two
//     sides.
//   - Voxels keep their hardness: a hard inside voxel uncovered in phase 2 becomes a hard
//     boundary voxel; hard voxels never become outside or inside-from-boundary.
// Invariants kept: outside voxels are soft; no inside voxel is 26-adjacent to an outside
// voxel; the outside stays 6-connected to the padding. Property 3 (boundary voxels with an
// outside face neighbour are hard or frozen) does NOT hold afterwards: phase 1 makes new soft
// boundary voxels next to the outside, and phase 2 uncovers soft inside voxels.
#ifndef MEMBRANE_CORE_MESH_RELAXATION_H_
#define MEMBRANE_CORE_MESH_RELAXATION_H_

#include <cstdint>

#include "absl/status/statusor.h"
#include "core/base/cancel_token.h"
#include "core/base/progress_meter.h"
#include "core/engine/voxel_grid.h"

namespace membrane {

struct RelaxationOptions {
  // |DLC| at which a voxel moves; the paper found 13 best in 3-D (lower values flatten the
  // membrane into coordinate and 45-degree planes, and let phase 2 undo phase 1).
  int threshold = 13;
  // Threads (<= 1: the calling thread) of the search for each phase's first qualifying voxels
  // (phase 1: a scan of the grid's planes; phase 2: a filter of the boundary voxels). The steps
  // themselves run one after the other in priority order. The result does not depend on the
  // count.
  int threads = 1;
};

struct RelaxationStats {
  int64_t phase1_moves = 0;      // boundary voxels made inside
  int64_t phase1_added = 0;      // outside voxels made boundary by those moves
  int64_t phase2_moves = 0;      // boundary voxels made outside
  int64_t phase2_uncovered = 0;  // inside voxels made boundary by those moves
  int64_t not_simple = 0;        // qualifying steps refused by the topology rule
};

// DLC(V) = #outside - #inside among the 26 neighbours of voxel `c`, in [-26, 26]. `c` must not
// lie on the array border.
int DiscreteLocalCurvature(const VoxelGrid& grid, const Coord& c);

// Input: a membrane grid (the engine's final DMS, invariants above holding), padding included.
// Effect: phase 1, then phase 2, as above, in place. Deterministic: the same grid for any
// options.threads.
// Returns the counts of each phase. Errors: InvalidArgument when threshold is outside [1, 26];
// Cancelled when `cancel` fired (polled every few thousand steps, and by every thread between
// the planes or chunks of a search, so within milliseconds); the grid is then a valid
// membrane, relaxed in part (every step is atomic). `progress` counts each phase (a half
// each): its search's planes or chunks, then the queued voxels taken, which reach the phase's
// end once every voxel first found has been taken (voxels queued again count on without
// moving it further). Counting changes nothing in the result.
// Memory: 8 bytes per non-hard boundary voxel (the list phase 2 starts from) and per queued
// voxel, beside the grid.
absl::StatusOr<RelaxationStats> Relax(VoxelGrid& membrane, const CancelToken& cancel,
                                      const RelaxationOptions& options = {},
                                      ProgressRange progress = ProgressRange());

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_RELAXATION_H_

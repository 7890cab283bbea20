// RecursiveContraction (paper section 4.3, Function 1) with CONTRACTION, UNDO CONTRACTION and
// FREEZING (section 4.2), on an explicit stack (algorithm-notes 6), with:
//   - ContractionOk of algorithm-notes 5,
//   - freezing the chain's start plate (algorithm-notes 8),
//   - the incursion test with generations and the thick-wall extension (notes 7 and 15),
//   - the topology guard (notes 12), and the depth bound at plate size 1 (notes 14),
//   - lean chains (fast-shrink.md section 3): only plate cells are written during a chain;
//     the INSIDE -> BOUNDARY conversion of the front and lateral sides is applied on commit.
#ifndef MEMBRANE_CORE_ENGINE_CONTRACTION_H_
#define MEMBRANE_CORE_ENGINE_CONTRACTION_H_

#include <cstdint>
#include <utility>
#include <vector>

#include "absl/container/flat_hash_set.h"
#include "core/base/cancel_token.h"
#include "core/engine/plate.h"
#include "core/engine/topology_guard.h"
#include "core/engine/voxel_grid.h"

namespace membrane {

struct ChainOptions {
  int plate_size = 1;          // n
  int generation_label = 1;    // written into the voxels this generation turns outside
  int depth_bound = 3;         // at small n, deeper front moves count as incursions; 0 = unbounded
  int depth_bound_max_plate = 1;  // the plate sizes the depth bound applies to: n <= this
  int thick_wall_run = 3;      // longest hard run of the thick-wall incursion test; 1 = paper
  bool topology_guard = true;  // algorithm-notes 12
  int guard_tunnel_min_plate = 5;  // tunnels away from hard voxels are allowed from this n
  int min_shell_voxels = 32;       // a split may not cut off a component this small
  int guard_short_loop_min_plate = 3;  // short-loop tunnels from this n (GuardOptions); 0 = off
  int guard_short_loop_steps = 6;      // ...within this many outside steps
  int guard_wall_notch_min_plate = 2;  // ...and beside a wall from this n; 0 = off
  // Count the removals the handle retry's strict sizes would refuse (GuardOptions).
  bool classify_strict = false;
  int strict_tunnel_min_plate = 7;
  int strict_short_loop_min_plate = 4;
};

// kSkipped: the start plate no longer fits (nothing changed).
// The guard's part of the chain options.
inline GuardOptions GuardOptionsOf(const ChainOptions& o) {
  return GuardOptions{o.plate_size, o.guard_tunnel_min_plate, o.min_shell_voxels,
                      o.guard_short_loop_min_plate, o.guard_short_loop_steps,
                      o.guard_wall_notch_min_plate, o.classify_strict,
                      o.strict_tunnel_min_plate, o.strict_short_loop_min_plate};
}

enum class ChainOutcome { kCommitted, kBacktracked, kCancelled, kSkipped };

// Counters a chain adds to.
struct ChainCounters {
  int64_t contractions = 0;        // CONTRACTION operations applied
  int64_t undone_contractions = 0; // of which undone by a backtrack
  int64_t guard_refusals = 0;      // backtracks caused by the topology guard
  int64_t depth_refusals = 0;      // backtracks caused by the n = 1 depth bound
  int64_t loose_tunnels = 0;       // removals allowed that the strict sizes refuse (undone too)
};

class ChainRunner {
 public:
  // Keeps a reference to `grid`, which must outlive the runner.
  explicit ChainRunner(VoxelGrid& grid) : grid_(grid) {}

  // Runs one recursive contraction from `start`, a plate that ContractionOk accepts on the
  // current grid with strict states (cells outside or boundary soft, back side outside, at
  // least one boundary soft cell; checked here, kBacktracked with nothing changed if not).
  // On an incursion (or a guard or depth refusal) every contraction of the chain is undone and
  // the start plate's boundary soft voxels are frozen: kBacktracked. Otherwise the chain is
  // committed: kCommitted. When `cancel` fires, the chain is undone without freezing:
  // kCancelled. After any outcome the grid satisfies the membrane invariants it had before.
  ChainOutcome Run(const Plate& start, const ChainOptions& options, const CancelToken& cancel,
                   ChainCounters& counters);

  // Lowest and highest z (voxel coordinates) written by the last Run; lo > hi when none.
  std::pair<int, int> last_z_range() const { return {z_lo_, z_hi_}; }

 private:
  struct Region {  // cells [u_lo, u_hi] x [v_lo, v_hi] of one layer
    int u_lo, u_hi, v_lo, v_hi;
  };
  struct Frame {
    Plate plate;
    int next_move;
  };

  // True when every cell of `cells` at `layer` is outside or soft and not frozen (INSIDE soft
  // counts only when `lenient`: the deferred conversion), and `back` cells at layer - sign are
  // all outside. Sets `any_movable` when some cell is not outside.
  bool RegionOk(int o, int layer, const Region& cells, bool lenient, bool& any_movable) const;
  bool BackOk(int o, int layer, const Region& cells) const;
  // CONTRACTION of `cells`: each non-outside cell becomes outside (after the topology guard),
  // then the incursion test runs around the cleared cells. False on incursion or refusal.
  bool Contract(int o, int layer, const Region& cells);
  void UndoAll();
  void Freeze(const Plate& plate);
  void CommitConversions();
  void NoteZ(int64_t index);
  int64_t CellIndex(int o, int layer, int u, int v) const;
  static uint64_t PlateKey(const Plate& p) {
    return (static_cast<uint64_t>(p.layer) << 42) | (static_cast<uint64_t>(p.u0) << 21) |
           static_cast<uint64_t>(p.v0);
  }

  VoxelGrid& grid_;
  ChainOptions options_;
  ChainCounters* counters_ = nullptr;
  std::vector<std::pair<uint32_t, VoxelState>> log_;  // (voxel, state before) per cleared cell
  std::vector<Frame> stack_;
  absl::flat_hash_set<uint64_t> contracted_;  // plates contracted by this chain
  int z_lo_ = 0, z_hi_ = -1;
  int guard_refused_ = 0;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_CONTRACTION_H_

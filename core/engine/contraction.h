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
#include "core/engine/hard_voxel_points.h"
#include "core/engine/incursion_test.h"
#include "core/engine/plate.h"
#include "core/engine/topology_guard.h"
#include "core/engine/voxel_box.h"
#include "core/engine/voxel_grid.h"

namespace membrane {

// What counts as an incursion, and whether the topology guard runs (ShrinkOptions::chain).
struct ChainRules {
  int depth_bound = 3;            // algorithm-notes 14: at small n, deeper front moves count as
                                  // incursions; 0 = unbounded (the paper)
  int depth_bound_max_plate = 2;  // the plate sizes the depth bound applies to: n <= this
  int thick_wall_run = 3;         // algorithm-notes 15: longest hard run of the thick-wall
                                  // incursion test; 1 = the paper's test only
  // The thin-part exception of the thick-wall test (incursion_test.h, engine-decisions.md):
  // it does not fire when the run's two ends are joined through the outside within the
  // Chebyshev radius thick_wall_detour (0 = never) and the run's points lie at least
  // thin_part_min_spread voxels from their best plane (data on both sides; 0 = not read).
  int thick_wall_detour = 4;
  double thin_part_min_spread = 0.25;
  // A run of at most thin_wall_face_max_run hard voxels (the paper's test's one voxel
  // included) whose two ends face surfaces at least thin_wall_face_gap voxels apart
  // (thin_wall_faces.h) is a thin part whatever the detour, for plates of
  // thin_wall_face_min_plate and more: the chains that carve a thin-walled container's inside
  // through its mouth (incursion_test.h; 0 = not read).
  double thin_wall_face_gap = 0.6;
  int thin_wall_face_min_plate = 20;
  int thin_wall_face_max_run = 2;
  bool topology_guard = true;     // algorithm-notes 12
};

// One generation's chains: its plate size n is guard.plate_size.
struct ChainOptions {
  int generation_label = 1;  // written into the voxels this generation turns outside
  ChainRules rules;
  GuardOptions guard;        // its plate size; its sizes are used when rules.topology_guard
  const HardVoxelPoints* points = nullptr;  // the input points (the thin-part exception)
  int plate_size() const { return guard.plate_size; }
  // The thin-part exception of the thick-wall test these options ask for.
  ThinPartRule thin_part() const {
    return {rules.thick_wall_detour, rules.thin_part_min_spread, points,
            plate_size() >= rules.thin_wall_face_min_plate ? rules.thin_wall_face_gap : 0.0,
            rules.thin_wall_face_max_run};
  }
};

// kSkipped: the start plate no longer fits (nothing changed).
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

  // Boxes holding every voxel whose state the last Run changed (a chain undone changed only
  // its frozen start plate); none when it changed none.
  const std::vector<VoxelBox>& last_written() const { return written_; }

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
  // Notes the cells [u_lo, u_hi] x [v_lo, v_hi] of `layer` in orientation o as written.
  void NoteWrite(int o, int layer, int u_lo, int u_hi, int v_lo, int v_hi);
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
  std::vector<VoxelBox> written_;  // see last_written()
  int guard_refused_ = 0;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_CONTRACTION_H_

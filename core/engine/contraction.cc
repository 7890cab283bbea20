#include "core/engine/contraction.h"

#include <algorithm>
#include <bit>

#include "core/engine/incursion_test.h"
#include "core/engine/local_topology.h"
#include "core/engine/topology_guard.h"

namespace membrane {
namespace {

enum Move { kFront = 0, kUpU, kDownU, kUpV, kDownV, kMoveCount };

}  // namespace

int64_t ChainRunner::CellIndex(int o, int layer, int u, int v) const {
  return grid_.Index(PlateCell(kOrientations[o], layer, u, v));
}

void ChainRunner::NoteWrite(int o, int layer, int u_lo, int u_hi, int v_lo, int v_hi) {
  const Orientation& orient = kOrientations[o];
  VoxelBox box;
  box.Add(PlateCell(orient, layer, u_lo, v_lo));
  box.Add(PlateCell(orient, layer, u_hi, v_hi));
  written_.push_back(box);
}

bool ChainRunner::RegionOk(int o, int layer, const Region& r, bool lenient,
                           bool& any_movable) const {
  const int64_t sv = grid_.strides()[kOrientations[o].v_axis()];
  const VoxelState* s = grid_.states().data();
  for (int u = r.u_lo; u <= r.u_hi; ++u) {
    int64_t i = CellIndex(o, layer, u, r.v_lo);
    for (int v = r.v_lo; v <= r.v_hi; ++v, i += sv) {
      const VoxelState state = s[i];
      if (IsOutside(state)) continue;
      if (state == kBoundarySoft || (lenient && state == kInsideSoft)) {
        any_movable = true;
        continue;
      }
      return false;
    }
  }
  return true;
}

bool ChainRunner::BackOk(int o, int layer, const Region& r) const {
  const Orientation& orient = kOrientations[o];
  const int64_t sv = grid_.strides()[orient.v_axis()];
  const VoxelState* s = grid_.states().data();
  const int back = layer - orient.sign;
  for (int u = r.u_lo; u <= r.u_hi; ++u) {
    int64_t i = CellIndex(o, back, u, r.v_lo);
    for (int v = r.v_lo; v <= r.v_hi; ++v, i += sv)
      if (!IsOutside(s[i])) return false;
  }
  return true;
}

bool ChainRunner::Contract(int o, int layer, const Region& r) {
  const Orientation& orient = kOrientations[o];
  const int64_t sv = grid_.strides()[orient.v_axis()];
  VoxelState* s = grid_.mutable_states().data();
  const VoxelState outside = OutsideState(options_.generation_label);
  int cu_lo = r.u_hi + 1, cu_hi = r.u_lo - 1, cv_lo = r.v_hi + 1, cv_hi = r.v_lo - 1;
  for (int u = r.u_lo; u <= r.u_hi; ++u) {
    int64_t i = CellIndex(o, layer, u, r.v_lo);
    for (int v = r.v_lo; v <= r.v_hi; ++v, i += sv) {
      if (IsOutside(s[i])) continue;
      if (options_.rules.topology_guard) {
        const GuardVerdict verdict = ClassifyRemoval(grid_, i, options_.guard);
        if (verdict == GuardVerdict::kRefused) {
          ++guard_refused_;
          return false;
        }
        if (verdict == GuardVerdict::kAllowedLoosely) ++counters_->loose_tunnels;
      }
      log_.emplace_back(static_cast<uint32_t>(i), s[i]);
      s[i] = outside;
      cu_lo = std::min(cu_lo, u);
      cu_hi = std::max(cu_hi, u);
      cv_lo = std::min(cv_lo, v);
      cv_hi = std::max(cv_hi, v);
    }
  }
  ++counters_->contractions;
  if (cu_lo > cu_hi) return true;
  NoteWrite(o, layer, cu_lo, cu_hi, cv_lo, cv_hi);
  // Incursion test on the hard and frozen voxels of the lateral side (this layer) and of the
  // front and lateral front sides (next layer) whose neighbourhood changed.
  for (int l = layer; l != layer + 2 * orient.sign; l += orient.sign) {
    for (int u = cu_lo - 1; u <= cu_hi + 1; ++u) {
      int64_t i = CellIndex(o, l, u, cv_lo - 1);
      for (int v = cv_lo - 1; v <= cv_hi + 1; ++v, i += sv) {
        if (IsHardOrFrozen(s[i]) && IncursionAt(grid_, i, options_.rules.thick_wall_run,
                                                options_.thin_part()))
          return false;
      }
    }
  }
  return true;
}

void ChainRunner::UndoAll() {
  VoxelState* s = grid_.mutable_states().data();
  for (auto it = log_.rbegin(); it != log_.rend(); ++it) s[it->first] = it->second;
  log_.clear();
}

void ChainRunner::Freeze(const Plate& p) {
  const int n = options_.plate_size();
  VoxelState* s = grid_.mutable_states().data();
  for (int u = p.u0; u < p.u0 + n; ++u)
    for (int v = p.v0; v < p.v0 + n; ++v) {
      const int64_t i = CellIndex(p.orientation, p.layer, u, v);
      if (s[i] == kBoundarySoft) {
        s[i] = kBoundaryFrozen;
      }
    }
  NoteWrite(p.orientation, p.layer, p.u0, p.u0 + n - 1, p.v0, p.v0 + n - 1);
}

void ChainRunner::CommitConversions() {
  const std::array<int64_t, 27>& offsets = grid_.block_offsets();
  VoxelState* s = grid_.mutable_states().data();
  for (const auto& [index, old] : log_) {
    for (int64_t offset : offsets) {
      VoxelState& n = s[index + offset];
      if (IsInside(n)) n |= kBoundaryBit;
    }
  }
  log_.clear();
}

ChainOutcome ChainRunner::Run(const Plate& start, const ChainOptions& options,
                              const CancelToken& cancel, ChainCounters& counters) {
  options_ = options;
  counters_ = &counters;
  log_.clear();
  stack_.clear();
  contracted_.clear();
  written_.clear();
  guard_refused_ = 0;
  const int n = options.plate_size();
  const Region full{start.u0, start.u0 + n - 1, start.v0, start.v0 + n - 1};
  bool movable = false;
  if (!RegionOk(start.orientation, start.layer, full, /*lenient=*/false, movable) || !movable ||
      !BackOk(start.orientation, start.layer, full)) {
    return ChainOutcome::kSkipped;
  }

  const Orientation& orient = kOrientations[start.orientation];
  const int o = start.orientation;
  const int dim_a = grid_.dim(orient.axis), dim_u = grid_.dim(orient.u_axis()),
            dim_v = grid_.dim(orient.v_axis());
  int64_t contractions_before = counters.contractions;
  bool depth_refused = false;
  bool failed = !Contract(o, start.layer, full);
  if (!failed) {
    contracted_.insert(PlateKey(start));
    stack_.push_back({start, 0});
  }
  while (!failed && !stack_.empty()) {
    if (cancel.cancelled()) {
      counters.undone_contractions += counters.contractions - contractions_before;
      UndoAll();
      return ChainOutcome::kCancelled;
    }
    Frame& top = stack_.back();
    if (top.next_move == kMoveCount) {
      stack_.pop_back();
      continue;
    }
    const int move = top.next_move++;
    const Plate p = top.plate;
    Plate t = p;
    Region cells{}, back{};
    bool check_back = true;
    switch (move) {
      case kFront: {
        t.layer += orient.sign;
        if (t.layer < 1 || t.layer > dim_a - 2) continue;
        check_back = false;  // the back side is p, all outside now
        auto done = [&](int du, int dv) {
          return contracted_.contains(PlateKey({o, t.layer, t.u0 + du, t.v0 + dv}));
        };
        if (done(-1, 0)) cells = {t.u0 + n - 1, t.u0 + n - 1, t.v0, t.v0 + n - 1};
        else if (done(1, 0)) cells = {t.u0, t.u0, t.v0, t.v0 + n - 1};
        else if (done(0, -1)) cells = {t.u0, t.u0 + n - 1, t.v0 + n - 1, t.v0 + n - 1};
        else if (done(0, 1)) cells = {t.u0, t.u0 + n - 1, t.v0, t.v0};
        else cells = {t.u0, t.u0 + n - 1, t.v0, t.v0 + n - 1};
        break;
      }
      case kUpU:
        if (++t.u0 + n - 1 > dim_u - 2) continue;
        cells = {t.u0 + n - 1, t.u0 + n - 1, t.v0, t.v0 + n - 1};
        break;
      case kDownU:
        if (--t.u0 < 1) continue;
        cells = {t.u0, t.u0, t.v0, t.v0 + n - 1};
        break;
      case kUpV:
        if (++t.v0 + n - 1 > dim_v - 2) continue;
        cells = {t.u0, t.u0 + n - 1, t.v0 + n - 1, t.v0 + n - 1};
        break;
      case kDownV:
        if (--t.v0 < 1) continue;
        cells = {t.u0, t.u0 + n - 1, t.v0, t.v0};
        break;
    }
    // A plate this chain contracted is all outside: no need to look at its cells.
    if (contracted_.contains(PlateKey(t))) continue;
    back = cells;
    movable = false;
    if (!RegionOk(o, t.layer, cells, /*lenient=*/true, movable) || !movable) continue;
    if (check_back && !BackOk(o, t.layer, back)) continue;
    if (move == kFront && n <= options.rules.depth_bound_max_plate &&
        options.rules.depth_bound > 0 &&
        (t.layer - start.layer) * orient.sign > options.rules.depth_bound) {
      depth_refused = true;
      failed = true;
      break;
    }
    if (!Contract(o, t.layer, cells)) {
      failed = true;
      break;
    }
    contracted_.insert(PlateKey(t));
    stack_.push_back({t, 0});
  }
  if (failed) {
    counters.undone_contractions += counters.contractions - contractions_before;
    if (guard_refused_ > 0) ++counters.guard_refusals;
    if (depth_refused) ++counters.depth_refusals;
    UndoAll();
    written_.clear();  // the chain's cells are as they were: only the freeze is left
    Freeze(start);
    return ChainOutcome::kBacktracked;
  }
  CommitConversions();
  // The conversions write the cleared cells' 26-neighbours.
  for (VoxelBox& box : written_) {
    for (int d = 0; d < 3; ++d) {
      box.lo[d] = std::max(box.lo[d] - 1, 0);
      box.hi[d] = std::min(box.hi[d] + 1, grid_.dim(d) - 1);
    }
  }
  return ChainOutcome::kCommitted;
}

}  // namespace membrane

#include "core/engine/piece_separation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <deque>
#include <utility>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/container/flat_hash_set.h"
#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "core/engine/flat_bitset.h"
#include "core/engine/local_topology.h"
#include "core/engine/point_gap_split.h"
#include "core/engine/post_process.h"
#include "core/engine/voxel_topology.h"

namespace membrane {
namespace {

constexpr int64_t kCancelPoll = 1 << 16;
// Waves are labelled by their piece in one byte.
constexpr uint8_t kNoWave = 255;
constexpr uint8_t kOutsideWave = 254;
constexpr size_t kMaxPieces = 254;

// A cut voxel and the pair of pieces whose waves met there (smaller label * 256 + larger).
struct CutVoxel {
  int64_t voxel;
  int pair;
};

// The pieces' own voxels with their pieces, sorted by voxel: the piece a ray meets.
using PieceLookup = std::vector<std::pair<int64_t, uint8_t>>;

// The piece of hard voxel `v`, or -1 when it belongs to none (stray points).
int PieceOf(const PieceLookup& lookup, int64_t v) {
  const auto it = std::lower_bound(lookup.begin(), lookup.end(), std::make_pair(v, uint8_t{0}));
  return it != lookup.end() && it->first == v ? it->second : -1;
}

// The piece of the first hard voxel met from `v` (exclusive) along `step` through the solid,
// or -1 when an outside voxel comes first or the hard voxel belongs to no piece.
int FirstPieceAlong(const VoxelGrid& grid, const PieceLookup& lookup, int64_t v, int64_t step) {
  const VoxelState* s = grid.states().data();
  // The array's padding is outside, so a ray ends within its longest axis.
  const int longest = std::max({grid.dim(0), grid.dim(1), grid.dim(2)});
  int64_t u = v;
  for (int k = 0; k < longest; ++k) {
    u += step;
    if (IsOutside(s[u])) return -1;
    if (IsHard(s[u])) return PieceOf(lookup, u);
  }
  return -1;
}

// Whether voxel `v` lies between the data of pieces `a` and `b`: along one of the 13 lattice
// lines through it, the first hard voxel met on one side is of `a` and on the other side of
// `b`, with no outside voxel before either. A cross-section of a solid whose data are the two
// pieces (a sphere's two caps) lies between them all over; a web in open space beside them,
// which reaches the outside along every line, does not.
bool LiesBetween(const VoxelGrid& grid, const PieceLookup& lookup, int64_t v, int a, int b) {
  for (int64_t step : grid.neighbour_offsets()) {
    if (step < 0) continue;  // each line once
    const int ahead = FirstPieceAlong(grid, lookup, v, step);
    if (ahead != a && ahead != b) continue;
    const int behind = FirstPieceAlong(grid, lookup, v, -step);
    if ((ahead == a && behind == b) || (ahead == b && behind == a)) return true;
  }
  return false;
}

// The largest ratio, over the pairs of pieces, of the voxels of the cut between them that a
// trial leaves outside (`carved`, sorted) and that lie between the two pieces' data
// (LiesBetween; every one when `lookup` is empty) to the smaller piece's hard voxels. Voxels
// carved that are not in `cut` (webs removed whole) belong to no pair. Read on the grid as it
// was before the trial.
double CutFraction(const VoxelGrid& grid, const PieceLookup& lookup, std::vector<CutVoxel> cut,
                   const std::vector<int64_t>& carved, const std::vector<int64_t>& piece_voxels) {
  std::sort(cut.begin(), cut.end(),
            [](const CutVoxel& a, const CutVoxel& b) { return a.voxel < b.voxel; });
  std::vector<int64_t> per_pair(256 * 256, 0);
  size_t k = 0;
  for (int64_t v : carved) {
    while (k < cut.size() && cut[k].voxel < v) ++k;
    if (k < cut.size() && cut[k].voxel == v &&
        (lookup.empty() || LiesBetween(grid, lookup, v, cut[k].pair / 256, cut[k].pair % 256))) {
      ++per_pair[cut[k].pair];
    }
  }
  double largest = 0.0;
  for (int pair = 0; pair < static_cast<int>(per_pair.size()); ++pair) {
    if (per_pair[pair] == 0) continue;
    const int64_t smaller = std::min(piece_voxels[pair / 256], piece_voxels[pair % 256]);
    largest = std::max(largest, static_cast<double>(per_pair[pair]) / static_cast<double>(smaller));
  }
  return largest;
}

// One cut tried on the grid and undone: only outside-ness matters to the topology count, and
// a kept cut is applied again with the membrane's states settled around it.
class CutTrial {
 public:
  struct Outcome {
    VoxelTopology topology;       // of the solid with the cut
    std::vector<int64_t> carved;  // voxels the cut leaves outside, in index order
    int64_t web_voxels = 0;       // of which in shells without data
    int64_t loops_closed = 0;     // cut voxels returned to close a loop the cut opened
    int64_t hard_carved = 0;      // of `carved`, hard voxels where two pieces touched
    int64_t hard_uncovered = 0;   // of those, without a face neighbour of their own data
  };

  // `scratch`: one byte a voxel, reused to hold the states of the voxels a trial changes.
  // `close_loops`: PieceSeparationOptions::close_cut_loops. `contacts`: the hard voxels the
  // cut may hold (where two pieces' hard voxels touch) and their pieces.
  CutTrial(VoxelGrid& grid, std::vector<VoxelState> scratch, bool close_loops,
           const absl::flat_hash_map<int64_t, uint8_t>& contacts)
      : close_loops_(close_loops), grid_(grid), s_(grid.mutable_states().data()),
        original_(std::move(scratch)), in_cut_(grid.size()), seen_(grid.size()),
        contacts_(contacts) {}

  // Turns `cut` (non-hard solid voxels, nearest the data first) outside, returns the enclosed
  // parts of it, removes the shells left without a hard voxel, returns every cut voxel whose
  // return is simple, counts the topology and restores the grid.
  absl::StatusOr<Outcome> Run(const std::vector<int64_t>& cut, const CancelToken& cancel) {
    changed_.clear();
    in_cut_.clear_all();
    loops_closed_ = 0;
    for (int64_t v : cut) {
      if (in_cut_.test(v)) continue;
      in_cut_.set(v);
      MakeOutside(v);
    }
    Outcome out;
    ReturnEnclosed(cut);
    if (!RemoveWebs(cut, out.web_voxels, cancel) || !Refill(cut, cancel)) {
      Restore();
      return absl::CancelledError("reconstruction cancelled");
    }
    out.loops_closed = loops_closed_;
    out.topology = ComputeVoxelTopology(grid_);
    for (int64_t v : changed_) {
      if (!IsOutside(s_[v])) continue;
      out.carved.push_back(v);
      if (!IsHard(original_[v])) continue;
      ++out.hard_carved;
      if (!KeptByOwnData(v)) ++out.hard_uncovered;
    }
    std::sort(out.carved.begin(), out.carved.end());
    Restore();
    return out;
  }

 private:
  void MakeOutside(int64_t v) {
    original_[v] = s_[v];
    changed_.push_back(v);
    s_[v] = OutsideState(0);
  }
  void Restore() {
    for (int64_t v : changed_) s_[v] = original_[v];
  }

  // Whether hard voxel `v`, outside in this trial, has a face neighbour that is a hard voxel in
  // the solid and not of another piece: the face between them is then on the membrane, within
  // one voxel of every point of `v`.
  bool KeptByOwnData(int64_t v) const {
    const auto own = contacts_.find(v);
    const auto st = grid_.strides();
    for (int d = 0; d < 3; ++d)
      for (int64_t n : {v - st[d], v + st[d]}) {
        if (!IsHard(s_[n])) continue;
        const auto other = contacts_.find(n);
        if (other == contacts_.end() || own == contacts_.end() || other->second == own->second)
          return true;
      }
    return false;
  }

  // Cut voxels enclosed by the solid (the interior of an object far from its data) are no
  // separation: each 6-component of them with no face neighbour outside before returns.
  void ReturnEnclosed(const std::vector<int64_t>& cut) {
    seen_.clear_all();
    std::vector<int64_t> part;
    const auto st = grid_.strides();
    for (int64_t v : cut) {
      if (seen_.test(v)) continue;
      part.assign(1, v);
      seen_.set(v);
      bool open = false;
      for (size_t k = 0; k < part.size(); ++k)
        for (int d = 0; d < 3; ++d)
          for (int64_t n : {part[k] - st[d], part[k] + st[d]}) {
            if (!IsOutside(s_[n])) continue;
            if (!in_cut_.test(n)) {
              open = true;
            } else if (!seen_.test(n)) {
              seen_.set(n);
              part.push_back(n);
            }
          }
      if (!open)
        for (int64_t n : part) s_[n] = original_[n];
    }
  }

  // Shells left without data beside the cut are webs: removed whole. A flood stops at the
  // first hard voxel, or at a voxel an earlier flood saw (that flood met data: a flood that
  // meets none sees its whole shell).
  bool RemoveWebs(const std::vector<int64_t>& cut, int64_t& web_voxels, const CancelToken& cancel) {
    seen_.clear_all();
    std::vector<int64_t> shell;
    for (int64_t v : cut) {
      if (!IsOutside(s_[v])) continue;
      if (cancel.cancelled()) return false;
      for (int64_t off : grid_.neighbour_offsets()) {
        const int64_t n = v + off;
        if (IsOutside(s_[n]) || seen_.test(n)) continue;
        shell.assign(1, n);
        seen_.set(n);
        bool has_data = IsHard(s_[n]);
        for (size_t k = 0; k < shell.size() && !has_data; ++k)
          for (int64_t o : grid_.neighbour_offsets()) {
            const int64_t m = shell[k] + o;
            if (IsOutside(s_[m])) continue;
            if (seen_.test(m) || IsHard(s_[m])) {
              has_data = true;
              break;
            }
            seen_.set(m);
            shell.push_back(m);
          }
        if (!has_data) {
          for (int64_t m : shell) MakeOutside(m);
          web_voxels += static_cast<int64_t>(shell.size());
        }
      }
    }
    return true;
  }

  // Cut voxels return to the solid, nearest the data first, while their return is simple and
  // keeps the membrane face-connected (a face neighbour in the solid): what stays outside is
  // what the separation needs. Then each cut voxel whose return closes a loop of the outside
  // returns too (the solid around it one 26-component, so no shells join; the outside around
  // it two or more 6-components, each still reaching the outside the grid had before the
  // trial, so no cavity forms): such a loop runs through the cut itself, a handle the cut
  // opened in a piece where the waves met inside it, not a gap the data show. The simple
  // returns then go on around it.
  bool Refill(const std::vector<int64_t>& cut, const CancelToken& cancel) {
    std::deque<int64_t> refill(cut.begin(), cut.end());
    int64_t polls = 0;
    auto is_solid = [](VoxelState x) { return !IsOutside(x); };
    for (bool returned = true; returned;) {
      while (!refill.empty()) {
        if (++polls % kCancelPoll == 0 && cancel.cancelled()) return false;
        const int64_t v = refill.front();
        refill.pop_front();
        if (!IsOutside(s_[v])) continue;
        const uint32_t solid = NeighbourhoodMask(grid_, v, is_solid);
        if ((solid & FaceNeighboursMask()) == 0 || !IsSimple(solid)) continue;
        Return(v, refill);
      }
      returned = false;
      if (!close_loops_) break;
      for (int64_t v : cut) {
        if (++polls % kCancelPoll == 0 && cancel.cancelled()) return false;
        if (!IsOutside(s_[v])) continue;
        const uint32_t solid = NeighbourhoodMask(grid_, v, is_solid);
        if ((solid & FaceNeighboursMask()) == 0 || CountT26(solid) != 1 ||
            CountT6(~solid & kAll27) < 2) {
          continue;
        }
        s_[v] = original_[v];
        const bool open = FacesReachOldOutside(v);
        s_[v] = OutsideState(0);
        if (!open) continue;
        Return(v, refill);
        ++loops_closed_;
        returned = true;
      }
    }
    return true;
  }

  // Returns cut voxel `v` to the solid and queues its cut neighbours still outside.
  void Return(int64_t v, std::deque<int64_t>& refill) {
    s_[v] = original_[v];
    for (int64_t off : grid_.neighbour_offsets())
      if (in_cut_.test(v + off) && IsOutside(s_[v + off])) refill.push_back(v + off);
  }

  // True when every outside face neighbour of `v` reaches, by face steps through the outside,
  // a voxel outside and not in the cut: one the grid had outside before the trial, which
  // reaches the array border (the grid had no cavity), or one of a web removed whole, which
  // borders that outside. The flood crosses only cut voxels, so it costs no more than the cut.
  bool FacesReachOldOutside(int64_t v) {
    const auto st = grid_.strides();
    for (int d = 0; d < 3; ++d)
      for (int64_t start : {v - st[d], v + st[d]}) {
        if (!IsOutside(s_[start])) continue;
        flood_.assign(1, start);
        flooded_.clear();
        flooded_.insert(start);
        bool reached = false;
        for (size_t k = 0; k < flood_.size() && !reached; ++k) {
          const int64_t u = flood_[k];
          if (!in_cut_.test(u)) {
            reached = true;
            break;
          }
          for (int e = 0; e < 3; ++e)
            for (int64_t n : {u - st[e], u + st[e]})
              if (IsOutside(s_[n]) && flooded_.insert(n).second) flood_.push_back(n);
        }
        if (!reached) return false;
      }
    return true;
  }

  const bool close_loops_;
  int64_t loops_closed_ = 0;
  VoxelGrid& grid_;
  VoxelState* s_;
  std::vector<VoxelState> original_;
  std::vector<int64_t> changed_;
  FlatBitset in_cut_;
  FlatBitset seen_;
  std::vector<int64_t> flood_;
  absl::flat_hash_set<int64_t> flooded_;
  const absl::flat_hash_map<int64_t, uint8_t>& contacts_;
};

}  // namespace

absl::StatusOr<PieceSeparationStats> SeparateDataPieces(VoxelGrid& grid,
                                                        const PieceSeparationOptions& options,
                                                        const CancelToken& cancel,
                                                        const HardVoxelPoints* points) {
  if (options.min_piece_fraction <= 0 || options.min_piece_fraction > 0.5 ||
      !(options.split_reach >= 0) ||
      options.far_steps < 1 || options.near_far_steps < 0 ||
      options.near_far_steps >= options.far_steps || !(options.max_cut_fraction > 0)) {
    return absl::InvalidArgumentError(
        absl::StrCat("piece separation options out of range: min_piece_fraction ",
                     options.min_piece_fraction, " (0..0.5], far_steps ", options.far_steps,
                     " (1 or more), near_far_steps ", options.near_far_steps,
                     " (0..far_steps - 1), max_cut_fraction ", options.max_cut_fraction,
                     " (above 0), split_reach ", options.split_reach, " (0 or more)"));
  }
  PieceSeparationStats stats;
  if (!options.enabled) return stats;
  const auto start = std::chrono::steady_clock::now();
  auto done = [&] {
    stats.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return stats;
  };
  auto cancelled = [] { return absl::CancelledError("reconstruction cancelled"); };
  VoxelState* s = grid.mutable_states().data();
  // The pieces: big 26-components of hard voxels, split where two objects' hard voxels touch
  // but their points do not come within split_reach of each other across the contact (their
  // hard voxels there may then be cut).
  absl::StatusOr<DataPieces> found =
      FindDataPieces(grid, options.split_reach > 0 ? points : nullptr, options.split_reach,
                     options.min_piece_fraction, cancel);
  if (!found.ok()) return found.status();
  stats.pieces = found->count;
  if (found->count < 2) return done();
  std::vector<std::vector<int64_t>> pieces = std::move(found->pieces);
  const bool split = found->split;

  // Waves from every piece at once through the solid, one 26-step a layer (one byte a voxel
  // while this runs, only when the data has two or more pieces). The cut: the non-hard solid
  // voxels where two pieces' waves meet, and the non-hard boundary voxels farther than
  // far_steps (and near_far_steps, for the third trial) from every piece (webs in open space,
  // or across a piece's own loops); in the waves' order, nearest the data first.
  if (pieces.size() > kMaxPieces) return done();
  // Outside voxels hold kOutsideWave: the spread reads one byte a neighbour, not two.
  std::vector<uint8_t> wave(static_cast<size_t>(grid.size()));
  for (int64_t i = 0; i < grid.size(); ++i) wave[i] = IsOutside(s[i]) ? kOutsideWave : kNoWave;
  std::vector<int64_t> frontier, next;
  // The pieces' own voxels, when two pieces' hard voxels can touch.
  FlatBitset in_piece(split ? grid.size() : 0);
  for (size_t p = 0; p < pieces.size(); ++p)
    for (int64_t v : pieces[p]) {
      wave[v] = static_cast<uint8_t>(p);
      frontier.push_back(v);
      if (split) in_piece.set(v);
    }
  PieceLookup lookup;
  if (options.between_only) {
    for (size_t p = 0; p < pieces.size(); ++p)
      for (int64_t v : pieces[p]) lookup.emplace_back(v, static_cast<uint8_t>(p));
    std::sort(lookup.begin(), lookup.end());
  }
  std::vector<int64_t> piece_voxels;
  for (const std::vector<int64_t>& piece : pieces)
    piece_voxels.push_back(static_cast<int64_t>(piece.size()));
  std::vector<std::vector<int64_t>>().swap(pieces);
  FlatBitset in_cut(grid.size());
  // `far` holds the voxels past near_far_steps (past far_steps when that is 0) in the waves'
  // order: those past far_steps are its tail, from far_split on.
  std::vector<int64_t> cut, far;
  size_t far_split = 0;
  const int first_far_layer =
      options.near_far_steps > 0 ? options.near_far_steps : options.far_steps;
  std::vector<CutVoxel> cut_pairs;
  // Hard voxels of two pieces that touch, and their pieces.
  absl::flat_hash_map<int64_t, uint8_t> contacts;
  auto add_to_cut = [&](int64_t v, int pair) {
    if ((IsHard(s[v]) && !contacts.contains(v)) || in_cut.test(v)) return;
    in_cut.set(v);
    cut.push_back(v);
    cut_pairs.push_back({v, pair});
  };
  bool meet = false;
  int64_t polls = 0;
  for (int layer = 0; !frontier.empty(); ++layer) {
    for (const int64_t v : frontier) {
      if (++polls % kCancelPoll == 0 && cancel.cancelled()) return cancelled();
      if (layer > first_far_layer && !IsHard(s[v])) far.push_back(v);
      const uint8_t own = wave[v];
      for (int64_t off : grid.neighbour_offsets()) {
        const int64_t n = v + off;
        const uint8_t other = wave[n];
        if (other == own || other == kOutsideWave) continue;
        if (other == kNoWave) {
          wave[n] = own;
          next.push_back(n);
        } else {
          meet = true;
          const int pair = std::min(other, own) * 256 + std::max(other, own);
          if (layer == 0 && split && in_piece.test(n)) {
            contacts.emplace(v, own);
            contacts.emplace(n, other);
          }
          add_to_cut(v, pair);
          add_to_cut(n, pair);
        }
      }
    }
    if (layer <= options.far_steps) far_split = far.size();
    frontier.swap(next);
    next.clear();
  }
  if (!meet) return done();
  // The cut's own voxels leave the far lists, which keep their order.
  size_t far_kept = 0, split_kept = 0;
  for (size_t k = 0; k < far.size(); ++k) {
    if (k == far_split) split_kept = far_kept;
    if (!in_cut.test(far[k])) far[far_kept++] = far[k];
  }
  if (far_split >= far.size()) split_kept = far_kept;
  far.resize(far_kept);
  far_split = split_kept;

  const VoxelTopology before = ComputeVoxelTopology(grid);
  // The waves' bytes now hold the states of the voxels a trial changes.
  CutTrial trial(grid, std::move(wave), options.close_cut_loops, contacts);
  absl::StatusOr<CutTrial::Outcome> between = trial.Run(cut, cancel);
  if (!between.ok()) return between.status();
  stats.cut_fraction =
      CutFraction(grid, lookup, std::move(cut_pairs), between->carved, piece_voxels);
  // Shells that can hold a piece of data: no fewer voxels than the smallest piece's hard
  // voxels. A cut that only splits off slivers (a few stray points cut loose) separates no
  // pieces.
  const int64_t smallest_piece = *std::min_element(piece_voxels.begin(), piece_voxels.end());
  auto piece_shells = [&](const VoxelTopology& t) {
    return std::count_if(t.voxels.begin(), t.voxels.end(),
                         [&](int64_t n) { return n >= smallest_piece; });
  };
  auto better = [&](const CutTrial::Outcome& trial) {
    const VoxelTopology& after = trial.topology;
    return trial.hard_uncovered == 0 && piece_shells(after) > piece_shells(before) &&
           TotalGenus(after) <= TotalGenus(before) && after.cavities <= before.cavities;
  };
  stats.shells_before = before.shells;
  stats.genus_before = TotalGenus(before);
  const CutTrial::Outcome* kept = nullptr;
  absl::StatusOr<CutTrial::Outcome> with_far, with_near_far;
  int kept_far_steps = 0;  // the kept trial's far webs (0: the cut between the pieces)
  // A cut between two pieces as large as a piece's data spans a solid's whole cross-section:
  // the two caps of a closed surface whose data miss a band around it, or a lid on its pot,
  // not two objects: nothing is tried further. Otherwise the far voxels are tried too, also
  // when the cut between the pieces alone leaves more loops than before: webs in open space
  // beside the cut can hold them (cow-spot-belt 1.5x: 3 shells, genus 5 without them, 4 with).
  if (stats.cut_fraction <= options.max_cut_fraction) {
    if (better(*between)) kept = &*between;
    const size_t between_size = cut.size();
    if (far_split < far.size()) {
      cut.insert(cut.end(), far.begin() + static_cast<std::ptrdiff_t>(far_split), far.end());
      with_far = trial.Run(cut, cancel);
      if (!with_far.ok()) return with_far.status();
      if (better(*with_far)) {
        kept = &*with_far;
        kept_far_steps = options.far_steps;
      }
    }
    // Webs that stand nearer the data: taken only for fewer handles on the same shells as a
    // separation the trials above made, never as a separation of its own (a cut this close
    // to the data can slice one object's solid into many shells: the pinhole cube's faces),
    // and a separation they already make as clean keeps its smaller cut.
    if (kept != nullptr && far_split > 0) {
      cut.resize(between_size);
      cut.insert(cut.end(), far.begin(), far.end());
      with_near_far = trial.Run(cut, cancel);
      if (!with_near_far.ok()) return with_near_far.status();
      if (better(*with_near_far) &&
          with_near_far->topology.shells == kept->topology.shells &&
          TotalGenus(with_near_far->topology) < TotalGenus(kept->topology)) {
        kept = &*with_near_far;
        kept_far_steps = options.near_far_steps;
      }
    }
  }
  const VoxelTopology& shown = kept != nullptr ? kept->topology : between->topology;
  stats.shells_after = shown.shells;
  stats.genus_after = TotalGenus(shown);
  stats.cavities_after = shown.cavities;
  if (kept == nullptr) return done();
  for (int64_t v : kept->carved) CarveToOutside(grid, v);
  stats.separated = true;
  stats.web_voxels = kept->web_voxels;
  stats.loops_closed = kept->loops_closed;
  stats.far_steps_cut = kept_far_steps;
  stats.cut_voxels = static_cast<int64_t>(kept->carved.size()) - kept->web_voxels;
  stats.hard_cut_voxels = kept->hard_carved;
  return done();
}

}  // namespace membrane

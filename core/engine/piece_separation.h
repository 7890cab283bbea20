// Separating pieces of data that the shrink joined into one shell (issue 18; docs/
// engine-decisions.md "Pieces of data separated after the shrink").
//
// Objects a few voxels apart (cow-spot-belt: 5.0 and 5.5 voxels at 1x) come out of the shrink
// as one shell: incursion freezes cascade on frozen voxels and leave plugs in the gaps and
// frozen sheets in open space between the objects, which no local rule tells from a wall over
// a data gap. After the shrink the data tell it: the points fill separate pieces (26-components
// of hard voxels, more than 2 voxels apart, so a tube of one voxel around the data keeps them
// apart too), and every solid path from one piece to another crosses the place where waves
// from the pieces, spread through the solid, meet.
#ifndef MEMBRANE_CORE_ENGINE_PIECE_SEPARATION_H_
#define MEMBRANE_CORE_ENGINE_PIECE_SEPARATION_H_

#include <cstdint>

#include "absl/status/statusor.h"
#include "core/base/cancel_token.h"
#include "core/engine/hard_voxel_points.h"
#include "core/engine/voxel_grid.h"

namespace membrane {

struct PieceSeparationOptions {
  bool enabled = true;
  // A piece of data is a 26-component of hard voxels holding at least this fraction of them;
  // smaller ones (stray points) belong to whichever piece reaches them first.
  double min_piece_fraction = 0.01;
  // Boundary voxels farther than this (26-steps through the solid) from every piece are cut
  // too: webs in open space, between the pieces or across a piece's own loops.
  int far_steps = 5;
  // The far webs tried once more from this many steps (0: not tried, else below far_steps)
  // when a trial before passed: kept when it passes with the same shells and fewer handles.
  // The shrink's webs between thin parts stand on voxels nearer the data when the voxel is
  // larger (cow-spot-belt: held 7 steps from the data at 1x, 4 at 1.5x).
  int near_far_steps = 3;
  // A cut between two pieces that stays outside with more voxels than this fraction of the
  // smaller piece's hard voxels spans a solid's whole cross-section (a closed surface whose data
  // miss a band around it), not a plug or a sheet between objects: the trial is refused.
  double max_cut_fraction = 0.33;
  // The size test counts only the cut voxels that lie between the two pieces' data (a lattice
  // line through the voxel meets one piece's hard voxels on one side and the other's on the
  // other side before the outside): a web in open space that the cut crosses, beside the
  // objects, spans no solid's cross-section. False: every cut voxel counts.
  bool between_only = true;
  // A cut voxel whose return to the solid closes a loop of the outside (no shells joined, no
  // cavity made) returns after the simple returns: the loop runs through the cut, a handle
  // the cut opened, not one the data show.
  bool close_cut_loops = true;
  // A 26-component of hard voxels is split into the classes of its voxels whose points come
  // within this many voxels of each other (SplitAtPointGaps: two objects whose one-voxel tubes
  // do not touch, their hard voxels meeting at corners); 0: not split. The hard voxels where
  // two such pieces touch may then be cut, each only where it keeps a face neighbour holding
  // its own piece's points in the solid (that face lies within one voxel of its points).
  double split_reach = 2.0;
};

struct PieceSeparationStats {
  int pieces = 0;              // pieces of data (after the split by their points)
  bool separated = false;      // the cut was kept
  int64_t cut_voxels = 0;      // voxels turned outside and kept outside
  int64_t hard_cut_voxels = 0; // of which hard: where two pieces' hard voxels touched
  int64_t web_voxels = 0;      // voxels of shells without data removed with the cut
  int64_t loops_closed = 0;    // cut voxels returned to close a loop the cut opened
  int far_steps_cut = 0;       // the kept trial's far webs: far_steps or near_far_steps
                               // (0: the cut between the pieces alone)
  // Topology before and with the cut (whether kept or not), when a cut was tried.
  int shells_before = 0, shells_after = 0;
  int genus_before = 0, genus_after = 0;
  int cavities_after = 0;
  // The largest ratio, over the pairs of pieces whose waves meet, of the voxels the cut between
  // them leaves outside to the smaller piece's hard voxels (0 when no cut was tried).
  double cut_fraction = 0.0;
  double seconds = 0.0;
};

// Input: a shrunk grid (the membrane invariants hold).
// Effect: when two pieces of data lie in one shell, waves from every piece spread through the
// solid (26-steps, breadth first). A cut is tried on the grid and undone: its non-hard voxels
// are turned outside, the enclosed parts of it return, shells left without a hard voxel are
// removed, and every cut voxel whose return to the solid is (26,6)-simple and face-connected
// returns, nearest the data first (so what stays outside is what the topology change needs);
// then (close_cut_loops) every cut voxel whose return closes a loop of the outside without
// joining shells or making a cavity returns, and the simple returns go on around it.
// A trial passes when it gives more shells that can hold a piece (no fewer voxels than the
// smallest piece's hard voxels), no more summed genus and no more cavities (topology counts).
// First the cut between the pieces (the non-hard voxels where two pieces' waves meet). When it
// leaves outside no more than max_cut_fraction of the smaller piece's hard voxels for every
// pair of pieces whose waves meet (stats.cut_fraction), the same cut with every non-hard voxel
// farther than far_steps from the pieces is tried too, then the same cut with every non-hard
// voxel farther than near_far_steps when one of those passed. The second trial when it
// passes, else the first when it passes, is the choice, unless the third passes with as many
// shells and a smaller summed genus: then the third. The choice is applied: its voxels turned
// outside with the membrane's states settled around them (CarveToOutside). Otherwise the grid
// is unchanged.
// With `points` (the hard voxels' points; nullptr: none) and split_reach above 0, a 26-component
// of hard voxels is split into the pieces SplitAtPointGaps finds, and the hard voxels of two
// pieces that are 26-adjacent join the cut between them: a trial that leaves such a voxel
// outside without a face neighbour that is a hard voxel in the solid and not of another piece
// is refused, so the points of a voxel cut stay within one voxel of a face between the solid
// and the outside. Every other hard voxel stays; stats.hard_cut_voxels counts those carved.
// A trial's size test counts the cut voxels between the two pieces' data (between_only).
// Costs one byte a voxel and two bitsets while it runs, only when the data has two or more
// pieces that meet. Cancelled when `cancel` fires (the grid is then unchanged).
absl::StatusOr<PieceSeparationStats> SeparateDataPieces(VoxelGrid& grid,
                                                        const PieceSeparationOptions& options,
                                                        const CancelToken& cancel,
                                                        const HardVoxelPoints* points = nullptr);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_PIECE_SEPARATION_H_

// Refill of channels carved through data gaps (issue 17, cause 3): on scanner clouds the
// membrane enters the solid through a part the scanner did not see and carves a blind channel
// behind walls whose data lies on their far side. The channel's own walls hold no data.
// And of pockets carved behind data walls (issue 18): plates that get through a sparse scan's
// gaps hollow the solid behind its scanned walls; a hollow entered through two gaps is a
// handle around the solid's own interior.
#ifndef MEMBRANE_CORE_ENGINE_GAP_REFILL_H_
#define MEMBRANE_CORE_ENGINE_GAP_REFILL_H_

#include <cstdint>

#include "absl/status/statusor.h"
#include "core/base/cancel_token.h"
#include "core/engine/voxel_grid.h"

namespace membrane {

struct GapRefillOptions {
  bool enabled = true;
  // A voxel is in a gap when no hard voxel lies within this Chebyshev distance (voxels): the
  // surface's gap test (hole caps) at the voxel's scale.
  int gap_radius = 2;
  // It lies behind gap walls when, of the 6 axis rays from it, at least this many enter the
  // solid through two non-hard voxels and meet a hard voxel further on (from inside a channel
  // every way but the way in runs into the solid's unscanned interior; from a concavity seen
  // from outside, rays meet the scanned walls first or leave through the opening).
  int min_enclosed_rays = 4;
  // And at most this many of its rays leave through the outside to the grid's border without
  // meeting the solid: a channel has one way out; a gap between two parts (an unscanned
  // belly between legs) opens two or more ways.
  int max_open_rays = 1;
  // Pockets behind data walls: an outside voxel (not of label 0: the padding and the piece
  // separation's cut) whose rays meet a hard voxel with the outside again within
  // pocket_wall_depth voxels behind it (a data wall seen from its inside: the object's surface
  // between the voxel and the outside) on at least pocket_backed_rays of its 6 axis rays,
  // each within pocket_reach voxels, and with at most max_open_rays rays leaving to the
  // array border without meeting a hard voxel, is in the region too, near data or not.
  // 0 turns pockets off.
  int pocket_backed_rays = 5;
  int pocket_wall_depth = 3;
  int pocket_reach = 32;
  // A 6-component of pocket voxels in which more than this share have an open ray (the other
  // five backed) is the inside of an open container seen through its mouth, not a pocket:
  // it is left alone.
  double max_open_pocket_share = 0.25;
  // Inside pockets, once no simple addition is left, an addition that closes a loop of the
  // outside (the solid around it one 26-component, the outside two or more 6-components
  // that stay joined elsewhere: no cavity) is made too, at most this many times: a handle
  // whose loop runs through the solid's interior seen through a gap. 0: simple additions only.
  int max_pocket_loops = 64;
};

struct GapRefillStats {
  int64_t refilled_voxels = 0;  // outside voxels returned to the solid
  int64_t pocket_voxels = 0;     // region voxels that pass the pocket test only
  int loops_closed = 0;          // non-simple additions that closed a loop of the outside
  double seconds = 0;            // wall time of the refill (set by the shrink that runs it)
};

// Input: a shrunk grid (the membrane invariants hold; every outside voxel 6-connected to the
// array border).
// Effect: returns to the solid every outside voxel that is in a gap and behind gap walls, or
// in a pocket behind data walls that is not an open container's inside (see
// GapRefillOptions), and reached from the membrane through such voxels, that is 6-adjacent
// to the solid when it is added and whose addition is (26,6)-simple, repeating until none is
// left, from the membrane inwards. So the fill starts
// only on membrane far from any data or inside a pocket, never joins two shells and never
// makes a cavity. Simple additions change no topology; when none is left, a pocket voxel
// whose addition closes a loop of the outside is added (at most max_pocket_loops times), one
// handle less each, and the simple fill goes on. A refilled voxel with an outside neighbour
// is FROZEN BOUNDARY (Property 3), others INSIDE; a boundary voxel left with no outside
// neighbour becomes INSIDE: the membrane invariants still hold.
// The region is read once, on the grid as it comes (the fill's own voxels would block the
// rays). Memory: 8 bytes per grid row and axis (the hard voxels' extremes per row; those
// along z once more per thread while they are read, up to 8 threads), a bit per block of 4^3
// voxels (whether it holds a hard voxel: the gap test's shortcut), the runs of non-outside
// voxels the rays search (outside_runs.h: 4 bytes per grid row and axis and 8 a run, at most
// an eighth of a byte a voxel; past that, a bit per block of 8^3 voxels that the rays step
// over, outside_blocks.h), two bits a voxel (the region and the voxels read out of it: 512 MB
// on a 2e9-voxel grid) and hash sets of the pocket voxels; each loop-closing trial searches
// at most 2^20 outside voxels.
// The grid's rows, its runs (or blocks) and the seeds are read on `threads` (>= 1), a slab of z
// planes a task, and the fill runs on the calling thread: the same grid for any count.
// Errors: Cancelled when `cancel` fires (the grid is then a valid membrane, partly
// refilled); InvalidArgument for options out of range.
absl::StatusOr<GapRefillStats> RefillGapChannels(VoxelGrid& grid, const GapRefillOptions& options,
                                                 const CancelToken& cancel, int threads = 1);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_GAP_REFILL_H_

// Opening real holes that the shrink left plugged (issue 18; docs/engine-decisions.md "Plugged
// holes opened from the data").
//
// A hole through the data narrower than the guard's tunnel plates (a disk pierced by a hole 4.8
// voxels wide) stays closed: plates reach it from both faces, but the incursion test and the
// topology guard cannot tell its rim from a wall with a dig behind it, so a plug of soft and
// frozen voxels is left at its waist. After the shrink the whole membrane is known, and the
// data tell the two apart: a real hole's plug is surrounded by data facing it (the hole's own
// walls), its two faces are far apart through the outside, and the data leave a passage at
// least a voxel clear; a plug over a data hole in a wall has the wall's data around it, facing
// along the passage, and a web between thin parts has open air or more web beside it.
#ifndef MEMBRANE_CORE_ENGINE_HOLE_OPENING_H_
#define MEMBRANE_CORE_ENGINE_HOLE_OPENING_H_

#include <cstdint>

#include "absl/status/statusor.h"
#include "core/base/cancel_token.h"
#include "core/engine/hard_voxel_points.h"
#include "core/engine/voxel_grid.h"

namespace membrane {

struct HoleOpeningOptions {
  bool enabled = true;
  // Longest plug crossed: non-hard voxels on a straight 6-step staircase along one of the 13
  // lattice directions, outside at both ends.
  int max_plug = 8;
  // Rays across the plug from its middle voxel, along the lattice directions perpendicular to
  // the staircase: none may reach the outside within ring_radius voxels, at least
  // min_data_rays meet a hard voxel, and each hard voxel met must face the plug: the normal of
  // its points (3x3x3 voxels) makes a cosine below max_facing_cos with the staircase.
  int ring_radius = 5;
  int min_data_rays = 3;
  double max_facing_cos = 0.5;
  // The hard voxels within ring_radius - 1 of the middle voxel (and 3 voxels along the
  // staircase) lie in at least this many of 8 angular sectors around it: data all around.
  int min_sectors = 6;
  // When a hard voxel met does not face the plug, the plug is still a hole's when the data
  // line the passage: at least passage_sectors of the 8 sectors hold hard voxels (within
  // ring_radius - 1 of the middle voxel) both at offsets passage_from to passage_to along the
  // staircase and at -passage_to to -passage_from (a waist narrower than the 3x3x3 voxels of
  // a plane fit, whose walls curve inside them; passage_sectors 9: never).
  double passage_from = 1.5;
  double passage_to = 3.5;
  int passage_sectors = 4;
  // Only for a waist whose walls every ray across the plug meets within narrow_steps (the
  // plane fits' boxes then reach the plug's line), and with at least passage_facing_hits of
  // the hard voxels met still facing the plug: a thin wall's two scanned faces, crossed
  // through their data gaps, line a passage too, but face along it.
  int narrow_steps = 1;
  int passage_facing_hits = 2;
  // Every plug voxel's centre lies at least min_clearance (voxels) from every point: the
  // passage stays open in a tube of one voxel around the data. In a passage lined with data
  // (passage_sectors), a line parallel to the staircase through the same spot of every plug
  // voxel, one of the centres of a clearance_samples^3 subdivision of the voxel, will do
  // (1: centres only): a waist 2.4 voxels wide whose axis runs off the voxel centres.
  double min_clearance = 1.0;
  int clearance_samples = 3;
  // The two ends are not joined through the outside inside the cube of this radius around the
  // middle voxel: the plug closes a hole, not a notch.
  int join_radius = 16;
  // Plugs carved at most: bounds hostile clouds (each plug's topology change is counted in the
  // cube of join_radius around it, or over the grid when that cannot tell).
  int max_openings = 32;
  // A plug is no hole when every ray across it (as above) that meets data finds the outside
  // within wall_core_depth non-hard voxels past that data: it lies in the core of a thin wall,
  // between digs through the data gaps of the wall's two faces (PlugInsideWallCore); 0: not
  // tested.
  int wall_core_depth = 3;
  // Nor is it when, past a narrow waist, the points of the 3x3x3 block around more than half
  // of the hard voxels those rays meet lie at least wall_faces_spread voxels from their best
  // plane: the two faces of a wall thinner than the block, crossed through data gaps of both
  // (PlugBetweenWallFaces; the thin-part exception's two surfaces, ChainRules::
  // thin_part_min_spread); 0: not tested.
  double wall_faces_spread = 0.25;
};

struct HoleOpeningStats {
  int64_t opened = 0;         // plugs carved, each one more handle
  int64_t refused = 0;        // plugs whose carving would not add exactly one handle (undone)
  int64_t wall_cores = 0;     // plugs that passed the data tests but lie in a wall's core
                              // (or between a thin wall's faces)
  int64_t carved_voxels = 0;  // voxels turned outside
  int64_t whole_grid_counts = 0;  // plugs whose topology change was counted over the grid,
                                  // not around the plug (CountCarveLocally undecided)
  double seconds = 0.0;       // the search and the topology counts
};

// Input: a shrunk grid (the membrane invariants hold) and its input points (`points`; null:
// nothing is opened, there is no evidence to read).
// Effect: each plug that passes every test of HoleOpeningOptions, in voxel index order, is
// carved (its staircase turned outside, generation label 0; the inside voxels beside it become
// boundary and the soft ones on a face frozen, as the post-process's dents) when that adds
// exactly one handle and changes no shell or cavity count (the grid counted once by
// ComputeVoxelTopology, each carve around its plug by CountCarveLocally, or over the grid again
// where that cannot tell);
// otherwise it is restored. The invariants still hold after it. The search for plugs runs on
// `threads` (>= 1) until the first carve; the result is the same for any thread count.
// Cancelled when `cancel` fires (checked between slices; the grid is then valid with the plugs
// opened so far).
absl::StatusOr<HoleOpeningStats> OpenPluggedHoles(VoxelGrid& grid,
                                                  const HoleOpeningOptions& options,
                                                  const HardVoxelPoints* points,
                                                  const CancelToken& cancel, int threads = 1);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_HOLE_OPENING_H_

// The statistics JSON of `membrane reconstruct --stats-json FILE` (design/contracts.md).
#ifndef MEMBRANE_CORE_PIPELINE_STATS_JSON_H_
#define MEMBRANE_CORE_PIPELINE_STATS_JSON_H_

#include <string>

#include "core/pipeline/reconstruction_report.h"

namespace membrane {

// `report` as one JSON object, snake_case keys, times in seconds, counts as integers. Every
// key of design/contracts.md is present:
//   points, voxel_size, grid [nx, ny, nz] (the full voxel grid: data region plus
//   VoxelGrid::kPadding outside layers on each side), hard_voxels, density_ratio,
//   generations [{plate_size, soft_voxels, started_contractions, backtrackings, seconds}],
//   membrane {hard_voxels, frozen_voxels, soft_voxels, inside_hard_voxels,
//             inside_soft_voxels, shells} (the final DMS before relaxation; counts of
//             BOUNDARY voxels, then of INSIDE voxels),
//   mesh {vertices, faces, closed, manifold, oriented, shells, genus [per shell]},
//   seconds {decode, voxelize, shrink, relax, surface, encode, total}, peak_rss_bytes.
// Extra keys: data_grid (grid without padding), schedule, surface, relaxed; per generation
// generation, contractions, undone_contractions, guard_refusals, depth_refusals, passes,
// local_passes (of the passes, those whose snapshot was taken near the last pass's writes
// only), level (1, or the factor of the coarser grid that ran it);
// post_process {inside_hard_before, inside_hard_after, carved_voxels, bridge_voxels};
// handle_retry {ran, kept, from_generation, loose_tunnels, shells_before, genus_before,
// shells_after, genus_after, web_voxels, web_hard_rim, seconds} (HandleRetry);
// piece_separation {pieces, separated, cut_voxels, hard_cut_voxels, web_voxels, loops_closed,
// far_steps_cut,
// shells_before, genus_before, shells_after, genus_after, cavities_after, cut_fraction,
// seconds} (PieceSeparationStats; the topology counts 0 when no cut was tried);
// hole_opening {opened, refused, wall_core_kept, carved_voxels, whole_grid_counts, seconds}
// (HoleOpeningStats; wall_core_kept: its wall_cores);
// gap_refill {refilled_voxels, pocket_voxels, loops_closed} (GapRefillStats);
// interior_guard {levels, core_voxels, frozen_voxels, band_frozen, released_voxels, seconds}
// (InteriorGuardStats; levels 0: no coarse membrane was built);
// coarse_plates {factor, generations, lifted_voxels, seconds} (CoarsePlatesStats; factor 0:
// every generation ran on the grid);
// topology_guard {tunnel_min_plate, object_tunnel_plate, dense_rim} (GuardSizes on the grid:
// a tunnel away from the data opens from a plate of tunnel_min_plate voxels, and below
// object_tunnel_plate (0: none) only with dense_rim n^2 hard voxels within n of it);
// relaxation {phase1_moves, phase1_added, phase2_moves, phase2_uncovered, not_simple};
// membrane.inside_frozen_voxels and membrane.genus; mesh.self_intersections and
// mesh.positive_volume; seconds.check. Non-finite reals are written as null.
std::string StatsJson(const ReconstructionReport& report);

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_STATS_JSON_H_

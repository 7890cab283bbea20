// The topology guard on contraction (algorithm-notes 12, with the small-split rule of
// docs/engine-decisions.md): may a soft voxel be turned outside without a spurious change of
// topology?
#ifndef MEMBRANE_CORE_ENGINE_TOPOLOGY_GUARD_H_
#define MEMBRANE_CORE_ENGINE_TOPOLOGY_GUARD_H_

#include <cstdint>

#include "core/engine/voxel_grid.h"

namespace membrane {

// The plate sizes from which the guard allows each kind of tunnel (ShrinkOptions::guard).
struct GuardSizes {
  int tunnel_min_plate = 5;      // tunnels away from hard voxels are allowed from this n
  int short_loop_min_plate = 3;  // below tunnel_min_plate, short-loop tunnels from this n; 0 = off
  int short_loop_steps = 6;      // ...whose two sides are joined within this many outside steps
  int wall_notch_min_plate = 2;  // short-loop tunnels beside a wall from this n; 0 = off
  int min_shell_voxels = 32;     // a split may not cut off a component this small
  // Below this plate (0: no such plate) a tunnel away from hard voxels opened by a plate of n
  // also needs data all around it: at least dense_rim * n^2 hard voxels within Chebyshev
  // radius n (ShrinkOptions::tunnel_axis_ratio sets it from the grid's width).
  int object_tunnel_plate = 0;
  double dense_rim = 2.0;
};

struct GuardOptions {
  int plate_size = 1;  // n of the current generation
  GuardSizes sizes;
  // The handle retry's stricter sizes (StrictGuardSizes): with `classify_strict`,
  // ClassifyRemoval tells apart the removals that their tunnel_min_plate,
  // short_loop_min_plate and wall_notch_min_plate (0 = off) would refuse. They never change
  // the answer.
  bool classify_strict = false;
  GuardSizes strict{.tunnel_min_plate = 7, .short_loop_min_plate = 5, .wall_notch_min_plate = 5};
};

enum class GuardVerdict : uint8_t {
  kRefused,
  kAllowed,
  kAllowedLoosely,  // allowed, but the strict sizes would refuse it (a tunnel or a wall notch)
};

// Classifies the non-outside voxel at `index` in its 3x3x3 neighbourhood as if it were removed
// (T6 of the outside, T26 of the rest), with the sizes of options.sizes: true when it is
// simple; or a local split whose every part is a 26-component of more than min_shell_voxels
// voxels (mitosis); or a tunnel opened by a plate of at least tunnel_min_plate with no HARD
// voxel (frozen ones do not count) among its 26 neighbours, and below object_tunnel_plate
// with at least dense_rim * n^2 hard voxels within Chebyshev radius n; or such a tunnel (no hard
// neighbour) opened by a plate of at least short_loop_min_plate (when > 0) whose two sides are
// joined by an outside path of at most short_loop_steps voxels (TunnelClosesShortLoop): the
// notch that starts the split of a bridge about one voxel thick; or, with hard neighbours,
// such a short-loop tunnel opened by a plate of at least wall_notch_min_plate (when > 0) whose
// hard neighbours all lie in one face layer of the block (InOneFaceLayer) and whose two sides
// carry the same generation label (SameGenerationAcrossTunnel). `index` must not lie on the
// array border. ClassifyRemoval tells the same, and with options.classify_strict also whether
// the strict sizes would have refused (kAllowedLoosely): a tunnel away from hard voxels
// allowed below strict.tunnel_min_plate that is no short-loop tunnel at or above
// strict.short_loop_min_plate, or a wall notch below strict.wall_notch_min_plate (or with
// wall notches off there).
GuardVerdict ClassifyRemoval(const VoxelGrid& grid, int64_t index, const GuardOptions& options);
inline bool GuardAllowsRemoval(const VoxelGrid& grid, int64_t index, const GuardOptions& options) {
  return ClassifyRemoval(grid, index, options) != GuardVerdict::kRefused;
}

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_TOPOLOGY_GUARD_H_

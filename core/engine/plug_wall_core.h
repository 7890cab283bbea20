// A plug left in the core of a thin wall (docs/engine-decisions.md "Plugged holes opened from
// the data", the wall-core test).
//
// The shrink can dig into a wall 3-5 voxels thick through data gaps of its two faces (a cup's
// side sampled at about a point a voxel) and leave a thin plug between the two digs. Seen from
// the plug, such a dig passes the hole tests: data around it, facing it, clear of the points,
// its two ends far apart through the outside. What tells it from a real hole is what lies
// behind the data across the plug: a hole's walls have the solid behind them (a ray across the
// passage enters the data and stays in it), while a wall's faces, seen from its core, have the
// open air right behind them. A wall thinner than the 3x3x3 voxels of a plane fit (a cup's
// bottom of 2 voxels) has no non-hard core to walk: there the rays across the plug run between
// its two faces, and the points around every hard voxel they meet lie on both faces, where a
// hole's walls are one surface around the passage.
#ifndef MEMBRANE_CORE_ENGINE_PLUG_WALL_CORE_H_
#define MEMBRANE_CORE_ENGINE_PLUG_WALL_CORE_H_

#include <cstdint>

#include "core/engine/hard_voxel_points.h"
#include "core/engine/voxel_grid.h"

namespace membrane {

// Input: a grid, a plug's middle voxel `mid` and its staircase direction `dir` (a lattice
// direction), the ring radius of the hole tests and a wall depth.
// Returns true when, of the lattice rays from `mid` perpendicular to `dir` (walked at most
// `ring_radius` voxels through non-hard voxels, stopped by an inside voxel), at least one meets
// a hard voxel and every one that does finds an outside voxel within `depth` non-hard voxels
// past the hard voxels it entered: the plug lies inside a wall whose faces it sees from behind.
// False otherwise (no data met, or some data with the solid behind it).
bool PlugInsideWallCore(const VoxelGrid& grid, int64_t mid, const Coord& dir, int ring_radius,
                        int depth);

// Input: as PlugInsideWallCore, the points, the steps within which the rays of a waist
// narrower than a plane fit meet data (HoleOpeningOptions::narrow_steps) and a spread in
// voxels.
// Returns true when some ray across the plug (the same rays) meets data farther than
// `narrow_steps` from `mid` and, of the hard voxels the rays meet, more than half have the
// points of their 3x3x3 block at least `min_spread` from their best plane
// (HardVoxelPoints::PlaneSpread): two surfaces, the faces of a wall thinner than the block,
// between which the plug crosses through data gaps of both. A hole's walls are one surface
// around the passage (a spread of their noise); only a waist whose every ray meets data within
// `narrow_steps` has blocks that reach across it and read its walls' curvature, and it is
// not read. False otherwise.
bool PlugBetweenWallFaces(const VoxelGrid& grid, const HardVoxelPoints& points, int64_t mid,
                          const Coord& dir, int ring_radius, int narrow_steps,
                          double min_spread);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_PLUG_WALL_CORE_H_

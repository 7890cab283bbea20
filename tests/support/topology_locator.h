// Where the handles and the merges of a DMS are, in voxel coordinates, so that a topology test
// that fails can be diagnosed from its output alone.
#ifndef MEMBRANE_TESTS_SUPPORT_TOPOLOGY_LOCATOR_H_
#define MEMBRANE_TESTS_SUPPORT_TOPOLOGY_LOCATOR_H_

#include <string>

#include "core/engine/voxel_grid.h"

namespace membrane::testing {

// One line per finding, for the solid (non-outside voxels) of `grid`:
// - every shell of genus > 0: the loops of its handles, as the arcs that remain when the solid
//   is thinned homotopically (simple voxels removed until none is left), each by its length
//   and the voxel nearest its centroid;
// - every pair of large hard components (at least 1% of the hard voxels) that share a shell:
//   the voxel where a breadth-first search through the solid from each reaches the other first
//   (the narrowest contact between the two pieces of data).
// Coordinates are voxel (x, y, z) with the model coordinates of the voxel centre beside them.
// Costs a few passes over the grid; meant for failure messages and tables, not the pipeline.
std::string LocateHandlesAndContacts(const VoxelGrid& grid, int max_items = 6);

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_SUPPORT_TOPOLOGY_LOCATOR_H_

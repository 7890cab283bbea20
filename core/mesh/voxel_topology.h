// The (26,6) topology of a voxel solid: what every surface of a membrane must reproduce
// (algorithm-notes 12-13, membrane-quality.md recipe 3). The solid is the set of non-outside
// voxels with 26-adjacency; the outside uses 6-adjacency.
#ifndef MEMBRANE_CORE_MESH_VOXEL_TOPOLOGY_H_
#define MEMBRANE_CORE_MESH_VOXEL_TOPOLOGY_H_

#include <vector>

#include "core/engine/voxel_grid.h"

namespace membrane {

struct VoxelTopology {
  // 26-connected components of non-outside voxels.
  int shells = 0;
  // Genus of each component's boundary surface, in the order of the components' first voxel
  // (lowest index): 1 - chi, chi the Euler characteristic of the union of the component's
  // closed cubes.
  std::vector<int> genus;
};

// Input: a grid whose border layer is outside (the membrane's padding guarantees it) and whose
// outside voxels are all 6-connected to the border (a membrane has no cavities; with a cavity
// the boundary of a component has several surfaces and `genus` no longer describes it).
// Output: shells and genus per shell, as a closed manifold surface of the solid must have them.
// Cost: O(voxels), one int32 label per voxel.
VoxelTopology ComputeVoxelTopology(const VoxelGrid& grid);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_VOXEL_TOPOLOGY_H_

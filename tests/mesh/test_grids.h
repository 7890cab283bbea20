// Hand-built voxel grids for the mesh tests: solids marked directly in a VoxelGrid, no shrink.
#ifndef MEMBRANE_TESTS_MESH_TEST_GRIDS_H_
#define MEMBRANE_TESTS_MESH_TEST_GRIDS_H_

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/engine/voxel_grid.h"
#include "core/geometry/point_cloud.h"

namespace membrane::testing {

// A cubic grid of n^3 voxels (padding included) of size `voxel_size`, all OutsideState(0).
VoxelGrid OutsideGrid(int n, double voxel_size = 1.0, std::array<double, 3> origin = {0, 0, 0});

// Makes every voxel where `solid(x, y, z)` holds non-outside, then classifies the solid as a
// membrane: voxels with an outside 26-neighbour become `boundary`, the others `inside`.
void MarkSolid(VoxelGrid& grid, const std::function<bool(int, int, int)>& solid,
               VoxelState boundary = kBoundaryHard, VoxelState inside = kInsideSoft);

// Re-classifies the non-outside voxels as above (after hand edits).
void ClassifyMembrane(VoxelGrid& grid, VoxelState boundary = kBoundaryHard,
                      VoxelState inside = kInsideSoft);

// Shapes, centred in an n^3 grid, sizes in voxels.
VoxelGrid BallGrid(int n, double radius);
VoxelGrid SolidTorusGrid(int n, double major_radius, double minor_radius);
VoxelGrid TwoBallsGrid(int n, double radius, double gap);
// Two single voxels sharing only an edge / only a corner.
VoxelGrid EdgeContactGrid();
VoxelGrid CornerContactGrid();
// Two cubes (side 4) sharing only an edge / only a corner: the contact in a thick solid.
VoxelGrid ThickEdgeContactGrid();
VoxelGrid ThickCornerContactGrid();
// A hollow box with walls `wall` thick and a 1-voxel pinhole through one wall.
VoxelGrid PinholeBoxGrid(int n, int wall);
// Random voxels (density p) in the grid's core, cavities filled: every odd configuration.
VoxelGrid RandomSolidGrid(int n, double p, uint32_t seed);

// The outside voxels not 6-connected to the array border become solid (membranes have no
// cavities).
void FillCavities(VoxelGrid& grid);

// `count` points uniformly on the sphere of `radius` (model units) around `centre`.
std::vector<Point3f> SpherePoints(int count, std::array<double, 3> centre, double radius,
                                  uint32_t seed);
// The voxel solid of a sampled sphere: voxels whose centre is within `radius` of `centre`,
// plus every voxel holding a point.
VoxelGrid SampledSphereGrid(int n, double voxel_size, std::array<double, 3> centre, double radius,
                            const std::vector<Point3f>& points);

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_MESH_TEST_GRIDS_H_

// Triangulation of the boundary polygons of voxel_boundary.h (a quad, possibly with edge
// midpoints or chamfer points) for the cuberille and the surface nets (membrane-quality.md
// recipe 3 step 4).
#ifndef MEMBRANE_CORE_MESH_POLYGON_SPLIT_H_
#define MEMBRANE_CORE_MESH_POLYGON_SPLIT_H_

#include <array>
#include <cstdint>
#include <vector>

#include "core/geometry/vec3.h"

namespace membrane {

// Appends the two triangles of quad (q0, q1, q2, q3), counter-clockwise seen from outside,
// split along the diagonal whose two triangles are the flatter pair (larger cosine between
// their normals): the other diagonal would fold the quad along its crease.
// `positions` is indexed by vertex id.
void SplitQuadFlatter(const std::array<int32_t, 4>& quad, const Vec3d* positions,
                      std::vector<std::array<int32_t, 3>>& triangles);

// Appends the fan triangulation of `polygon` (counter-clockwise, at least 3 vertices) from
// polygon[apex]. Fanning from an edge midpoint never creates an edge between the two ends of a
// split lattice edge, which would duplicate the edge of the other quad pair.
void SplitPolygonFan(const std::vector<int32_t>& polygon, int apex,
                     std::vector<std::array<int32_t, 3>>& triangles);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_POLYGON_SPLIT_H_

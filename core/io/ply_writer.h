// Writing PLY files: binary little endian, float32 x y z (double with an origin), float32
// vertex normals nx ny nz for meshes, int32 triangle lists.
#ifndef MEMBRANE_CORE_IO_PLY_WRITER_H_
#define MEMBRANE_CORE_IO_PLY_WRITER_H_

#include <string>

#include "core/geometry/point_cloud.h"
#include "core/geometry/triangle_mesh.h"

namespace membrane {

// The bytes of a binary little-endian PLY file holding `cloud`: one "vertex" element with
// float x, y, z, or, when cloud.origin is not zero, double x, y, z of position + origin.
// Never fails.
std::string EncodePlyPointCloud(const PointCloud& cloud);

// The bytes of a binary little-endian PLY file holding `mesh`: float x, y, z vertices (double
// position + origin when mesh.origin is not zero, as for clouds), each with float nx, ny, nz
// (AreaWeightedVertexNormals), and a "face" element with "property list uchar int
// vertex_indices". The caller has checked the face indices (see CheckFaceIndices); they are
// written as they are.
std::string EncodePlyMesh(const TriangleMesh& mesh);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_PLY_WRITER_H_

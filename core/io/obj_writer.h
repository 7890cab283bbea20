// Writing Wavefront OBJ text.
#ifndef MEMBRANE_CORE_IO_OBJ_WRITER_H_
#define MEMBRANE_CORE_IO_OBJ_WRITER_H_

#include <string>

#include "core/geometry/point_cloud.h"
#include "core/geometry/triangle_mesh.h"

namespace membrane {

// OBJ text with one "v x y z" line per point, numbers in the shortest form that reads back
// exactly. Never fails.
std::string EncodeObjPointCloud(const PointCloud& cloud);

// OBJ text with "v" lines, as many "vn" lines (AreaWeightedVertexNormals), and one
// "f a//a b//b c//c" line (1-based: vertex and its normal) per face. The caller has checked
// the face indices.
std::string EncodeObjMesh(const TriangleMesh& mesh);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_OBJ_WRITER_H_

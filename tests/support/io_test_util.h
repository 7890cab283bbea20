// Helpers shared by the io tests: scratch files, sample geometry, geometric comparisons.
#ifndef MEMBRANE_TESTS_SUPPORT_IO_TEST_UTIL_H_
#define MEMBRANE_TESTS_SUPPORT_IO_TEST_UTIL_H_

#include <array>
#include <string>
#include <vector>

#include "absl/strings/string_view.h"
#include "core/geometry/point_cloud.h"
#include "core/geometry/triangle_mesh.h"

namespace membrane::testing {

// Writes `bytes` to `path`, failing the test on error.
void WriteTestFile(const std::string& path, absl::string_view bytes);

// `n` deterministic pseudo-random points in [-scale, scale]^3, with awkward float values.
PointCloud SampleCloud(int n, float scale = 10.0f);

// A closed octahedron: 6 vertices, 8 outward CCW triangles.
TriangleMesh Octahedron();

// A closed UV-sphere-like mesh with roughly `n` vertices, for compression tests.
TriangleMesh SphereMesh(int rings, int segments);

// The largest distance from a point of `a` to its nearest point of `b` (brute force:
// keep the clouds small), per coordinate (Chebyshev), in model units.
double MaxNearestChebyshev(const std::vector<Point3f>& a, const std::vector<Point3f>& b);

// The triangles of `mesh` as position triples, each rotated to start at its smallest corner
// (keeping orientation), sorted: equal for meshes with the same triangles whatever the
// vertex and face order.
std::vector<std::array<Point3f, 3>> CanonicalTriangles(const TriangleMesh& mesh);

// Bytes of `value` in big-endian order, for hand-built binary files.
std::string BigEndianFloat(float value);
std::string BigEndianDouble(double value);
std::string LittleEndianFloat(float value);
std::string LittleEndianDouble(double value);

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_SUPPORT_IO_TEST_UTIL_H_

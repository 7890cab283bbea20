#include "tests/support/io_test_util.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>

#include "gtest/gtest.h"

namespace membrane::testing {
namespace {

template <typename T>
std::string Bytes(T value, bool big_endian) {
  std::string bytes(sizeof(T), '\0');
  std::memcpy(bytes.data(), &value, sizeof(T));
  if (big_endian == (std::endian::native == std::endian::little)) {
    std::reverse(bytes.begin(), bytes.end());
  }
  return bytes;
}

}  // namespace

void WriteTestFile(const std::string& path, absl::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  ASSERT_TRUE(out.good()) << "cannot write " << path;
}

PointCloud SampleCloud(int n, float scale) {
  PointCloud cloud;
  uint64_t state = 0x9E3779B97F4A7C15ull;
  const auto next = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<float>((state >> 40) / static_cast<double>(1ull << 24)) * 2.0f - 1.0f;
  };
  for (int i = 0; i < n; ++i) {
    cloud.points.push_back({next() * scale, next() * scale, next() * scale / 3.0f});
  }
  return cloud;
}

TriangleMesh Octahedron() {
  TriangleMesh mesh;
  mesh.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  mesh.faces = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return mesh;
}

TriangleMesh SphereMesh(int rings, int segments) {
  TriangleMesh mesh;
  const double pi = std::acos(-1.0);
  mesh.vertices.push_back({0, 0, 1});
  for (int r = 1; r < rings; ++r) {
    const double theta = pi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double phi = 2 * pi * s / segments;
      mesh.vertices.push_back({static_cast<float>(std::sin(theta) * std::cos(phi)),
                               static_cast<float>(std::sin(theta) * std::sin(phi)),
                               static_cast<float>(std::cos(theta))});
    }
  }
  mesh.vertices.push_back({0, 0, -1});
  const int south = static_cast<int>(mesh.vertices.size()) - 1;
  const auto ring = [&](int r, int s) { return 1 + (r - 1) * segments + (s % segments); };
  for (int s = 0; s < segments; ++s) mesh.faces.push_back({0, ring(1, s), ring(1, s + 1)});
  for (int r = 1; r + 1 < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      mesh.faces.push_back({ring(r, s), ring(r + 1, s), ring(r + 1, s + 1)});
      mesh.faces.push_back({ring(r, s), ring(r + 1, s + 1), ring(r, s + 1)});
    }
  }
  for (int s = 0; s < segments; ++s) {
    mesh.faces.push_back({south, ring(rings - 1, s + 1), ring(rings - 1, s)});
  }
  return mesh;
}

double MaxNearestChebyshev(const std::vector<Point3f>& a, const std::vector<Point3f>& b) {
  double worst = 0;
  for (const Point3f& p : a) {
    double best = std::numeric_limits<double>::infinity();
    for (const Point3f& q : b) {
      double d = 0;
      for (int axis = 0; axis < 3; ++axis) d = std::max(d, std::fabs(double{p[axis]} - q[axis]));
      best = std::min(best, d);
    }
    worst = std::max(worst, best);
  }
  return worst;
}

std::vector<std::array<Point3f, 3>> CanonicalTriangles(const TriangleMesh& mesh) {
  std::vector<std::array<Point3f, 3>> triangles;
  for (const auto& face : mesh.faces) {
    std::array<Point3f, 3> t = {mesh.vertices[face[0]], mesh.vertices[face[1]],
                                mesh.vertices[face[2]]};
    const auto smallest = std::min_element(t.begin(), t.end()) - t.begin();
    std::rotate(t.begin(), t.begin() + smallest, t.end());
    triangles.push_back(t);
  }
  std::sort(triangles.begin(), triangles.end());
  return triangles;
}

std::string BigEndianFloat(float value) { return Bytes(value, true); }
std::string BigEndianDouble(double value) { return Bytes(value, true); }
std::string LittleEndianFloat(float value) { return Bytes(value, false); }
std::string LittleEndianDouble(double value) { return Bytes(value, false); }

}  // namespace membrane::testing

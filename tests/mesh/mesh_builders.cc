#include "tests/mesh/mesh_builders.h"

#include <cmath>
#include <numbers>

namespace membrane::testing {

TriangleMesh CubeMesh(std::array<float, 3> lo, float size) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)
    m.vertices.push_back(
        {lo[0] + size * (i & 1), lo[1] + size * ((i >> 1) & 1), lo[2] + size * (i >> 2)});
  // Each face as a CCW quad seen from outside.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.faces.push_back({q[0], q[1], q[2]});
    m.faces.push_back({q[0], q[2], q[3]});
  }
  return m;
}

TriangleMesh TorusMesh(int rings, int segments, float major_radius, float minor_radius) {
  TriangleMesh m;
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const double u = 2 * std::numbers::pi * i / rings, v = 2 * std::numbers::pi * j / segments;
      const double r = major_radius + minor_radius * std::cos(v);
      m.vertices.push_back({static_cast<float>(r * std::cos(u)),
                            static_cast<float>(r * std::sin(u)),
                            static_cast<float>(minor_radius * std::sin(v))});
    }
  auto id = [&](int i, int j) {
    return ((i + rings) % rings) * segments + (j + segments) % segments;
  };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      m.faces.push_back({a, b, c});
      m.faces.push_back({a, c, d});
    }
  return m;
}

TriangleMesh Concat(const TriangleMesh& a, const TriangleMesh& b) {
  TriangleMesh m = a;
  const int32_t offset = static_cast<int32_t>(a.vertices.size());
  m.vertices.insert(m.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (auto f : b.faces) m.faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
  return m;
}

}  // namespace membrane::testing

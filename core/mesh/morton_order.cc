#include "core/mesh/morton_order.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/base/split_sort.h"

namespace membrane {
namespace {

// Spreads the low 21 bits of v so that two zero bits follow each one.
uint64_t Spread(uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffull;
  v = (v | v << 16) & 0x1f0000ff0000ffull;
  v = (v | v << 8) & 0x100f00f00f00f00full;
  v = (v | v << 4) & 0x10c30c30c30c30c3ull;
  v = (v | v << 2) & 0x1249249249249249ull;
  return v;
}

}  // namespace

void MortonOrder(TriangleMesh& mesh, double cell, std::vector<Point3f>* companion,
                 int threads) {
  const size_t nv = mesh.vertices.size();
  if (nv == 0) return;
  std::array<float, 3> lo = mesh.vertices[0];
  for (const Point3f& p : mesh.vertices)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]);
  // (key, index) side by side: the sort then compares contiguous pairs instead of looking the
  // keys up through the indices (half the sort's time). Unique pairs, so the order is the same
  // however the sort is split.
  std::vector<std::pair<uint64_t, int32_t>> keyed(nv);
  MakeAndSortUnique(keyed, threads, [&](size_t v) {
    uint64_t code = 0;
    for (int k = 0; k < 3; ++k) {
      const double c = std::floor((mesh.vertices[v][k] - lo[k]) / cell);
      code |= Spread(static_cast<uint64_t>(std::clamp(c, 0.0, double(0x1fffff)))) << k;
    }
    return std::pair<uint64_t, int32_t>{code, static_cast<int32_t>(v)};
  });
  std::vector<int32_t> order(nv);
  for (size_t i = 0; i < nv; ++i) order[i] = keyed[i].second;
  std::vector<int32_t> new_id(nv);
  std::vector<Point3f> vertices(nv);
  for (size_t i = 0; i < nv; ++i) {
    new_id[order[i]] = static_cast<int32_t>(i);
    vertices[i] = mesh.vertices[order[i]];
  }
  mesh.vertices = std::move(vertices);
  if (companion != nullptr) {
    std::vector<Point3f> moved(nv);
    for (size_t i = 0; i < nv; ++i) moved[i] = (*companion)[order[i]];
    *companion = std::move(moved);
  }
  // Faces by their lowest new vertex, stably: a counting sort, linear where a comparison sort
  // of the faces would take a tenth of the surface nets.
  std::vector<int32_t> start(nv + 1, 0);
  for (auto& f : mesh.faces) {
    for (int32_t& v : f) v = new_id[v];
    ++start[std::min({f[0], f[1], f[2]}) + 1];
  }
  for (size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<std::array<int32_t, 3>> faces(mesh.faces.size());
  for (const auto& f : mesh.faces) faces[start[std::min({f[0], f[1], f[2]})]++] = f;
  mesh.faces = std::move(faces);
}

}  // namespace membrane

#include "core/mesh/crossing_repair.h"

#include <algorithm>

#include "core/mesh/self_intersection.h"
#include "core/geometry/vec3.h"

namespace membrane {

CrossingRepair RepairCrossings(TriangleMesh& mesh, const std::vector<Point3f>& safe, int halvings) {
  CrossingRepair result;
  std::vector<int32_t> vertices;
  // Per vertex: how often it was moved back already. A vertex moved halfway `halvings` times
  // goes all the way next; one already at its safe position cannot move, so a round that moves
  // nothing ends the repair (only possible when `safe` itself crosses).
  std::vector<uint8_t> moves(mesh.vertices.size(), 0);
  for (;;) {
    const auto pairs = FindIntersectingFaces(mesh);
    ++result.checks;
    result.crossings_left = static_cast<int64_t>(pairs.size());
    if (pairs.empty()) return result;
    vertices.clear();
    for (const auto& [a, b] : pairs)
      for (int32_t f : {a, b})
        for (int32_t v : mesh.faces[f]) vertices.push_back(v);
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
    int64_t moved = 0;
    for (int32_t v : vertices) {
      if (mesh.vertices[v] == safe[v]) continue;
      const double keep = moves[v] < halvings ? 0.5 : 0.0;
      ++moves[v];
      const Vec3d s = ToVec3d(safe[v]);
      mesh.vertices[v] = ToPoint3f(s + keep * (ToVec3d(mesh.vertices[v]) - s));
      ++moved;
    }
    result.moved_vertices += moved;
    if (moved == 0) return result;
  }
}

}  // namespace membrane

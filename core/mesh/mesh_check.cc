#include "core/mesh/mesh_check.h"

#include <algorithm>
#include <array>
#include <numeric>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "core/mesh/self_intersection.h"
#include "core/mesh/triangle_intersection.h"
#include "core/geometry/vec3.h"

namespace membrane {
namespace {

// The share of a searching check's progress that its passes over faces and vertices take.
constexpr double kTopologyShare = 0.3;

class UnionFind {
 public:
  explicit UnionFind(int64_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int64_t Find(int64_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void Union(int64_t a, int64_t b) {
    a = Find(a);
    b = Find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<int64_t> parent_;
};

// Compressed rows: for each key, the list of values pushed for it. int32 items: a mesh has
// fewer than 2^31 / 6 faces.
struct Rows {
  std::vector<int64_t> start;
  std::vector<int32_t> items;
  int64_t size(int64_t k) const { return start[k + 1] - start[k]; }
};

template <typename EachFn>
Rows BuildRows(int64_t keys, EachFn each) {
  Rows rows;
  rows.start.assign(keys + 1, 0);
  each([&](int64_t k, int64_t) { ++rows.start[k + 1]; });
  for (int64_t k = 0; k < keys; ++k) rows.start[k + 1] += rows.start[k];
  rows.items.resize(rows.start[keys]);
  std::vector<int64_t> fill(rows.start.begin(), rows.start.end() - 1);
  each([&](int64_t k, int64_t v) { rows.items[fill[k]++] = static_cast<int32_t>(v); });
  return rows;
}


// One fan or cycle: the link edges (a, b) of the faces around a vertex form a connected graph
// of maximum degree 2. `nodes` and `label` are scratch buffers.
bool SingleFan(const std::vector<std::pair<int32_t, int32_t>>& link, std::vector<int32_t>& nodes,
               std::vector<int32_t>& label) {
  nodes.clear();
  for (auto [a, b] : link) {
    nodes.push_back(a);
    nodes.push_back(b);
  }
  std::sort(nodes.begin(), nodes.end());
  // Every node appears at most twice (degree <= 2).
  for (size_t i = 2; i < nodes.size(); ++i)
    if (nodes[i] == nodes[i - 2]) return false;
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  auto id = [&](int32_t v) {
    return static_cast<int32_t>(std::lower_bound(nodes.begin(), nodes.end(), v) - nodes.begin());
  };
  // Union-find over the link nodes, `label` as the parent array.
  label.resize(nodes.size());
  std::iota(label.begin(), label.end(), 0);
  auto find = [&](int32_t x) {
    while (label[x] != x) x = label[x] = label[label[x]];
    return x;
  };
  for (auto [a, b] : link) {
    const int32_t ra = find(id(a)), rb = find(id(b));
    label[std::max(ra, rb)] = std::min(ra, rb);
  }
  for (int32_t& l : label) l = find(l);
  for (int32_t l : label)
    if (l != 0) return false;
  return true;
}

}  // namespace

bool IsDegenerateFace(const TriangleMesh& mesh, const std::array<int32_t, 3>& f) {
  if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) return true;
  const Triangle3d t{ToVec3d(mesh.vertices[f[0]]), ToVec3d(mesh.vertices[f[1]]),
                     ToVec3d(mesh.vertices[f[2]])};
  const double e =
      std::max({SquaredNorm(t[1] - t[0]), SquaredNorm(t[2] - t[1]), SquaredNorm(t[0] - t[2])});
  // Relative test: sin(angle) below 1e-12 is zero area at double precision. On the canonical
  // normal, so that the answer does not depend on which vertex the face lists first.
  return SquaredNorm(CanonicalNormal(t)) <= 1e-24 * e * e;
}

MeshReport CheckMesh(const TriangleMesh& mesh, const CancelToken& cancel, int threads,
                     const std::vector<std::pair<int32_t, int32_t>>* known_crossings,
                     ProgressRange progress) {
  MeshReport r;
  const int64_t nv = static_cast<int64_t>(mesh.vertices.size());
  const int64_t nf = static_cast<int64_t>(mesh.faces.size());
  r.vertices = nv;
  r.faces = nf;
  // Progress: the face pass and the two vertex passes, then the crossing search when there is
  // one.
  const double topology_share = known_crossings != nullptr ? 1.0 : kTopologyShare;
  const ProgressRange topology = progress.Part(0, topology_share);
  topology.Begin(nf + 2 * nv);

  std::vector<char> valid(nf, 0);
  for (int64_t f = 0; f < nf; ++f) {
    const auto& t = mesh.faces[f];
    const bool in_range =
        t[0] >= 0 && t[0] < nv && t[1] >= 0 && t[1] < nv && t[2] >= 0 && t[2] < nv;
    if (!in_range) {
      ++r.invalid_faces;
      continue;
    }
    valid[f] = 1;
    if (IsDegenerateFace(mesh, t)) ++r.degenerate_faces;
  }
  topology.Add(nf);

  // Half-edges grouped by their lower endpoint: item = 2 * (3 * face + corner) + direction.
  const Rows edges_by_low = BuildRows(nv, [&](auto push) {
    for (int64_t f = 0; f < nf; ++f) {
      if (!valid[f]) continue;
      for (int k = 0; k < 3; ++k) {
        const int32_t a = mesh.faces[f][k], b = mesh.faces[f][(k + 1) % 3];
        push(std::min(a, b), 2 * (3 * f + k) + (a < b ? 0 : 1));
      }
    }
  });
  auto other_end = [&](int64_t item) {
    const int64_t he = item / 2;
    const auto& t = mesh.faces[he / 3];
    const int32_t a = t[he % 3], b = t[(he % 3 + 1) % 3];
    return std::max(a, b);
  };

  UnionFind shells_uf(nf);
  std::vector<int64_t> edge_shell_face;            // one face per undirected edge, for per-shell E
  std::vector<char> edge_ok;                       // edge has exactly two faces
  std::vector<std::pair<int32_t, int32_t>> group;  // (other end, item)
  for (int64_t v = 0; v < nv; ++v) {
    group.clear();
    for (int64_t i = edges_by_low.start[v]; i < edges_by_low.start[v + 1]; ++i)
      group.emplace_back(other_end(edges_by_low.items[i]), edges_by_low.items[i]);
    std::sort(group.begin(), group.end());
    for (size_t i = 0; i < group.size();) {
      size_t j = i;
      int forward = 0, backward = 0;
      while (j < group.size() && group[j].first == group[i].first) {
        (group[j].second % 2 == 0 ? forward : backward)++;
        shells_uf.Union(group[i].second / 6, group[j].second / 6);
        ++j;
      }
      const int count = forward + backward;
      if (count == 1) ++r.boundary_edges;
      if (count > 2) ++r.nonmanifold_edges;
      if (forward > 1 || backward > 1) ++r.misoriented_edges;
      edge_shell_face.push_back(group[i].second / 6);
      edge_ok.push_back(count == 2 && forward == 1);
      i = j;
    }
  }
  topology.Add(nv);

  // Faces around each vertex, for the fan test and per-shell vertex counts.
  const Rows faces_by_vertex = BuildRows(nv, [&](auto push) {
    for (int64_t f = 0; f < nf; ++f)
      if (valid[f])
        for (int k = 0; k < 3; ++k) push(mesh.faces[f][k], 3 * f + k);
  });

  // Shells, numbered by their first face.
  std::vector<int64_t> shell_of(nf, -1), root_to_shell(nf, -1);
  for (int64_t f = 0; f < nf; ++f) {
    if (!valid[f]) continue;
    const int64_t root = shells_uf.Find(f);
    if (root_to_shell[root] < 0) root_to_shell[root] = r.shells++;
    shell_of[f] = root_to_shell[root];
  }
  std::vector<int64_t> shell_v(r.shells, 0), shell_e(r.shells, 0), shell_f(r.shells, 0);
  std::vector<char> shell_good(r.shells, 1);
  std::vector<double> shell_volume(r.shells, 0);
  for (int64_t f = 0; f < nf; ++f) {
    if (!valid[f]) continue;
    ++shell_f[shell_of[f]];
    const auto& t = mesh.faces[f];
    const double vol = Dot(ToVec3d(mesh.vertices[t[0]]),
                           Cross(ToVec3d(mesh.vertices[t[1]]), ToVec3d(mesh.vertices[t[2]]))) /
                       6;
    shell_volume[shell_of[f]] += vol;
    r.volume += vol;
  }
  for (size_t e = 0; e < edge_shell_face.size(); ++e) {
    const int64_t s = shell_of[edge_shell_face[e]];
    ++shell_e[s];
    if (!edge_ok[e]) shell_good[s] = 0;
  }

  std::vector<std::pair<int32_t, int32_t>> link;
  std::vector<int64_t> vertex_shells;
  std::vector<int32_t> scratch_nodes, scratch_labels;
  for (int64_t v = 0; v < nv; ++v) {
    const int64_t n = faces_by_vertex.size(v);
    if (n == 0) {
      ++r.unreferenced_vertices;
      continue;
    }
    link.clear();
    vertex_shells.clear();
    for (int64_t i = faces_by_vertex.start[v]; i < faces_by_vertex.start[v + 1]; ++i) {
      const int64_t item = faces_by_vertex.items[i];
      const auto& t = mesh.faces[item / 3];
      const int k = static_cast<int>(item % 3);
      link.emplace_back(t[(k + 1) % 3], t[(k + 2) % 3]);
      vertex_shells.push_back(shell_of[item / 3]);
    }
    std::sort(vertex_shells.begin(), vertex_shells.end());
    vertex_shells.erase(std::unique(vertex_shells.begin(), vertex_shells.end()),
                        vertex_shells.end());
    for (int64_t s : vertex_shells) ++shell_v[s];
    if (!SingleFan(link, scratch_nodes, scratch_labels)) {
      ++r.nonmanifold_vertices;
      for (int64_t s : vertex_shells) shell_good[s] = 0;
    }
  }
  topology.Add(nv);

  r.closed = r.boundary_edges == 0 && r.nonmanifold_edges == 0;
  r.edge_manifold = r.nonmanifold_edges == 0;
  r.vertex_manifold = r.nonmanifold_vertices == 0;
  r.manifold = r.edge_manifold && r.vertex_manifold;
  r.oriented = r.misoriented_edges == 0;
  r.positive_volume = r.shells > 0;
  for (int s = 0; s < r.shells; ++s) {
    if (shell_volume[s] <= 0) r.positive_volume = false;
    const int64_t chi = shell_v[s] - shell_e[s] + shell_f[s];
    r.genus.push_back(shell_good[s] && chi % 2 == 0 ? static_cast<int>((2 - chi) / 2) : -1);
  }
  r.self_intersections =
      static_cast<int64_t>(known_crossings != nullptr
                               ? known_crossings->size()
                               : FindIntersectingFaces(mesh, cancel, threads,
                                                       progress.Part(topology_share, 1))
                                     .size());
  return r;
}

std::string MeshReportToJson(const MeshReport& r) {
  auto b = [](bool v) { return v ? "true" : "false"; };
  return absl::StrCat(
      "{\"vertices\": ", r.vertices, ", \"faces\": ", r.faces, ", \"closed\": ", b(r.closed),
      ", \"manifold\": ", b(r.manifold), ", \"edge_manifold\": ", b(r.edge_manifold),
      ", \"vertex_manifold\": ", b(r.vertex_manifold), ", \"oriented\": ", b(r.oriented),
      ", \"positive_volume\": ", b(r.positive_volume),
      ", \"volume\": ", absl::StrFormat("%.9g", r.volume),
      ", \"self_intersections\": ", r.self_intersections,
      ", \"degenerate_faces\": ", r.degenerate_faces, ", \"invalid_faces\": ", r.invalid_faces,
      ", \"unreferenced_vertices\": ", r.unreferenced_vertices,
      ", \"boundary_edges\": ", r.boundary_edges, ", \"nonmanifold_edges\": ", r.nonmanifold_edges,
      ", \"misoriented_edges\": ", r.misoriented_edges,
      ", \"nonmanifold_vertices\": ", r.nonmanifold_vertices, ", \"shells\": ", r.shells,
      ", \"genus\": [", absl::StrJoin(r.genus, ", "), "]}");
}

}  // namespace membrane

#include "core/mesh/voxel_boundary.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "core/base/parallel_tasks.h"
#include "core/engine/voxel_state_words.h"

namespace membrane {
namespace {

constexpr int kMaxFans = 8;

// The 12 quads inside the 2x2x2 block around a corner: quad (axis a, q) separates the two
// octants that differ only along a; q packs their bits along (a+1)%3 and (a+2)%3.
int QuadIndex(int axis, const std::array<int, 3>& bits) {
  return axis * 4 + bits[(axis + 1) % 3] + 2 * bits[(axis + 2) % 3];
}
int Octant(const std::array<int, 3>& bits) { return bits[0] | (bits[1] << 1) | (bits[2] << 2); }
std::array<int, 3> Bits(int octant) { return {octant & 1, (octant >> 1) & 1, (octant >> 2) & 1}; }

struct CornerFacts {
  int num_fans = 0;
  std::array<int8_t, 12> quad_fan{};  // fan of each boundary quad, -1 for other quads
  // Half-edge h = 2 * axis + (1 for the + direction): bit h set when the 4 voxels around it
  // form the diagonal pattern, and (second mask) when both of its quad pairs lie in one fan.
  uint8_t ambiguous = 0;
  uint8_t ambiguous_one_fan = 0;
  std::array<Vec3d, kMaxFans> centroid{};
  std::array<Vec3d, kMaxFans> outside_direction{};
  std::array<int8_t, kMaxFans> solid_octant{};
};

CornerFacts MakeCornerFacts(int config) {
  CornerFacts facts;
  auto solid = [&](int o) { return ((config >> o) & 1) != 0; };
  // Octants of quad i: low side (bit a = 0) and high side.
  std::array<std::array<int, 2>, 12> octants;
  std::array<bool, 12> boundary;
  for (int a = 0; a < 3; ++a)
    for (int q = 0; q < 4; ++q) {
      std::array<int, 3> bits{};
      bits[(a + 1) % 3] = q & 1;
      bits[(a + 2) % 3] = q >> 1;
      bits[a] = 0;
      const int lo = Octant(bits);
      bits[a] = 1;
      const int hi = Octant(bits);
      octants[a * 4 + q] = {lo, hi};
      boundary[a * 4 + q] = solid(lo) != solid(hi);
    }
  std::array<int, 12> parent;
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[x] != x) x = parent[x];
    return x;
  };
  auto unite = [&](int x, int y) { parent[find(x)] = find(y); };
  // Pair the quads around each half-edge from the corner.
  for (int a = 0; a < 3; ++a)
    for (int s = 0; s < 2; ++s) {
      std::array<int, 4> around{};
      int n = 0;
      for (int w = 0; w < 3; ++w) {
        if (w == a) continue;
        const int third = 3 - a - w;
        for (int t = 0; t < 2; ++t) {
          std::array<int, 3> bits{};
          bits[a] = s;
          bits[third] = t;
          const int quad = QuadIndex(w, bits);
          if (boundary[quad]) around[n++] = quad;
        }
      }
      if (n == 2) unite(around[0], around[1]);
      if (n == 4) {
        // Diagonal pattern: pair the two quads of each OUTSIDE octant, so the solid stays
        // joined along the edge and the outside octants stay apart.
        facts.ambiguous |= 1 << (2 * a + s);
        for (int o = 0; o < 8; ++o) {
          const auto bits = Bits(o);
          if (bits[a] != s || solid(o)) continue;
          int first = -1;
          for (int w = 0; w < 3; ++w) {
            if (w == a) continue;
            const int quad = QuadIndex(w, bits);
            if (first < 0)
              first = quad;
            else
              unite(first, quad);
          }
        }
      }
    }
  std::array<int, 12> root_fan;
  root_fan.fill(-1);
  facts.quad_fan.fill(-1);
  std::array<int, kMaxFans> quads_in_fan{};
  std::array<uint8_t, kMaxFans> outside_octants{};
  for (int i = 0; i < 12; ++i) {
    if (!boundary[i]) continue;
    const int root = find(i);
    if (root_fan[root] < 0) root_fan[root] = facts.num_fans++;
    const int fan = root_fan[root];
    facts.quad_fan[i] = static_cast<int8_t>(fan);
    const int axis = i / 4, q = i % 4;
    Vec3d centre{0, 0, 0};
    centre[(axis + 1) % 3] = (q & 1) ? 0.5 : -0.5;
    centre[(axis + 2) % 3] = (q >> 1) ? 0.5 : -0.5;
    facts.centroid[fan] = facts.centroid[fan] + centre;
    ++quads_in_fan[fan];
    const int out = solid(octants[i][0]) ? octants[i][1] : octants[i][0];
    const int in = solid(octants[i][0]) ? octants[i][0] : octants[i][1];
    outside_octants[fan] |= 1 << out;
    facts.solid_octant[fan] = static_cast<int8_t>(in);
  }
  for (int f = 0; f < facts.num_fans; ++f) {
    facts.centroid[f] = (1.0 / quads_in_fan[f]) * facts.centroid[f];
    for (int o = 0; o < 8; ++o)
      if ((outside_octants[f] >> o) & 1) {
        const auto bits = Bits(o);
        facts.outside_direction[f] =
            facts.outside_direction[f] +
            Vec3d{bits[0] ? 1.0 : -1.0, bits[1] ? 1.0 : -1.0, bits[2] ? 1.0 : -1.0};
      }
  }
  // Which ambiguous half-edges have both pairs in one fan.
  for (int a = 0; a < 3; ++a)
    for (int s = 0; s < 2; ++s) {
      if (!((facts.ambiguous >> (2 * a + s)) & 1)) continue;
      int fans[2], k = 0;
      for (int o = 0; o < 8; ++o) {
        const auto bits = Bits(o);
        if (bits[a] != s || solid(o)) continue;
        const int w = (a + 1) % 3;
        fans[k++] = facts.quad_fan[QuadIndex(w, bits)];
      }
      if (fans[0] == fans[1]) facts.ambiguous_one_fan |= 1 << (2 * a + s);
    }
  return facts;
}

const std::array<CornerFacts, 256>& Table() {
  static const std::array<CornerFacts, 256> table = [] {
    std::array<CornerFacts, 256> t;
    for (int c = 0; c < 256; ++c) t[c] = MakeCornerFacts(c);
    return t;
  }();
  return table;
}

// Counter-clockwise seen from the outside: (u, v) order for +a, reversed for -a, since
// u x v = +a.
constexpr int kPositiveOffsets[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
constexpr int kNegativeOffsets[4][2] = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};

// True when one of the 8 voxels from `s` on (along x) is solid with an outside face
// neighbour; the 8 voxels and their neighbours must exist. Outside is the top bit of a state.
bool AnyBoundaryFace(const VoxelState* s, const std::array<int64_t, 3>& st) {
  auto load = [&](int64_t offset) { return LoadStates8(s + offset); };
  const uint64_t solid = ~load(0) & kOutsideBits8;
  const uint64_t outside_neighbour =
      (load(-st[0]) | load(st[0]) | load(-st[1]) | load(st[1]) | load(-st[2]) | load(st[2])) &
      kOutsideBits8;
  return (solid & outside_neighbour) != 0;
}

// Appends to `list` the voxels of layer z that have a boundary face, by index in ascending
// order: the scan reads every voxel of the layer. The list depends on the grid alone.
void BoundaryVoxelsOfLayer(const VoxelGrid& grid, int z, std::vector<int64_t>& list) {
  const auto st = grid.strides();
  const auto& dims = grid.dims();
  const VoxelState* states = grid.states().data();
  for (int y = 1; y < dims[1] - 1; ++y)
    for (int x = 1; x < dims[0] - 1; ++x) {
      const int64_t i = grid.Index(x, y, z);
      // Eight voxels at a time where none has a boundary face (nearly everywhere).
      if ((x - 1) % 8 == 0 && x + 8 <= dims[0] - 1 && !AnyBoundaryFace(states + i, st)) {
        x += 7;
        continue;
      }
      if (IsOutside(states[i])) continue;
      bool face = false;
      for (int a = 0; a < 3 && !face; ++a)
        face = IsOutside(states[i - st[a]]) || IsOutside(states[i + st[a]]);
      if (face) list.push_back(i);
    }
}

// The boundary voxels of each layer z (1 .. dims[2] - 2), the layers side by side on
// `threads` threads.
std::vector<std::vector<int64_t>> BoundaryVoxelsByLayer(const VoxelGrid& grid, int threads) {
  const auto& dims = grid.dims();
  std::vector<std::vector<int64_t>> layers(static_cast<size_t>(dims[2]));
  RunTasks(threads, std::max(dims[2] - 2, 0), [&](int, int64_t task) {
    const int z = static_cast<int>(task) + 1;
    BoundaryVoxelsOfLayer(grid, z, layers[static_cast<size_t>(z)]);
  });
  return layers;
}

struct CornerEntry {
  // First fan vertex; -1: not made yet; -2 - k: the k-th corner the slab takes from the layer
  // below it.
  int32_t base = -1;
  uint8_t config = 0;
};

// True when a quad of a solid octant below the corner (octant bit 2 clear) has the corner
// among its own: that octant is solid and one of its three neighbours in the block is outside.
// Such a corner is made by the voxel layer below its lattice plane.
bool MadeByLayerBelow(int config) {
  for (int o = 0; o < 4; ++o) {
    if (!((config >> o) & 1)) continue;
    for (int a = 0; a < 3; ++a)
      if (!((config >> (o ^ (1 << a))) & 1)) return true;
  }
  return false;
}

// An edge midpoint's key: (lower lattice corner's index * 3 + axis, outside voxel's index).
using MidpointKey = std::pair<int64_t, int64_t>;

// The boundary of voxel layers [z0, z1), numbered from 0 in the one-thread order. Where the
// slab meets the layer below it (z0 > 1), the corners of lattice plane z0 and the midpoints of
// its edges that the layer below makes are taken from there: a quad's corner id -1 - (8 k + f)
// is fan f of the k-th of `below_corners`, a midpoint id -2 - k the k-th of `below_midpoints`.
struct SlabBoundary {
  BoundaryArray<VoxelBoundary::FanVertex> fan_vertices;
  BoundaryArray<VoxelBoundary::EdgeMidpoint> midpoints;
  BoundaryArray<VoxelBoundary::Quad> quads;
  int64_t corner_contacts = 0;
  std::vector<int64_t> below_corners;  // x + dim0 * y in lattice plane z0
  std::vector<MidpointKey> below_midpoints;
  // What the slab above takes: the corners of lattice plane z1 (x + dim0 * y, first fan
  // vertex) and the midpoints of its edges, sorted by position and key.
  std::vector<std::pair<int64_t, int32_t>> top_corners;
  std::vector<std::pair<MidpointKey, int32_t>> top_midpoints;
};

// The lattice corners met so far, by (x, y) in two planes: the quads of the voxels of layer z
// have their corners in lattice layers z and z + 1 (plane z & 1 and (z + 1) & 1), so a layer
// is forgotten once the scan has left it. Dense: a hash map here would take a third of the
// extraction.
struct CornerPlanes {
  std::array<std::vector<CornerEntry>, 2> corners;
  // The entries of each plane made so far: a new layer resets only those (clearing the whole
  // plane per layer wrote 8 bytes per voxel of the grid).
  std::array<std::vector<int64_t>, 2> made;

  void Reset(int plane) {
    for (int64_t at : made[plane]) corners[plane][at] = CornerEntry{};
    made[plane].clear();
  }
};

// The one-thread pass over layers [z0, z1): quads in voxel index order, a vertex for each fan
// of a corner and a midpoint for each ambiguous edge when first met. `layers`, when given,
// holds the boundary voxels of each layer; otherwise each layer is scanned here.
void BuildSlab(const VoxelGrid& grid, int z0, int z1,
               std::vector<std::vector<int64_t>>* layers, CornerPlanes& planes,
               SlabBoundary& out) {
  const auto& table = Table();
  const auto st = grid.strides();
  const VoxelState* states = grid.states().data();
  const int64_t plane_size = int64_t{grid.dim(0)} * grid.dim(1);
  for (auto& p : planes.corners)
    if (static_cast<int64_t>(p.size()) != plane_size) p.assign(plane_size, CornerEntry{});
  absl::flat_hash_map<MidpointKey, int32_t> midpoint_ids;
  // The layer below the slab made some corners of lattice plane z0 and midpoints of its edges.
  const bool below = z0 > 1;

  auto corner_config = [&](const Coord& c) {
    const int64_t base = grid.Index(c.x - 1, c.y - 1, c.z - 1);
    int config = 0;
    for (int o = 0; o < 8; ++o) {
      const int64_t j = base + (o & 1) * st[0] + ((o >> 1) & 1) * st[1] + (o >> 2) * st[2];
      if (!IsOutside(states[j])) config |= 1 << o;
    }
    return config;
  };
  auto corner_entry = [&](const Coord& c) -> CornerEntry {
    const int64_t at = c.x + int64_t{grid.dim(0)} * c.y;
    CornerEntry& entry = planes.corners[c.z & 1][at];
    if (entry.base == -1) {
      planes.made[c.z & 1].push_back(at);
      const int config = corner_config(c);
      entry.config = static_cast<uint8_t>(config);
      if (below && c.z == z0 && MadeByLayerBelow(config)) {
        entry.base = -2 - static_cast<int32_t>(out.below_corners.size());
        out.below_corners.push_back(at);
      } else {
        entry.base = static_cast<int32_t>(out.fan_vertices.size());
        for (int f = 0; f < table[config].num_fans; ++f)
          out.fan_vertices.push_back({c, static_cast<uint8_t>(config), static_cast<uint8_t>(f)});
        if (IsCornerContact(config)) ++out.corner_contacts;
      }
    }
    return entry;
  };

  const auto& dims = grid.dims();
  const int64_t row = dims[0];
  const int64_t plane = row * dims[1];
  std::vector<int64_t> scanned;
  for (int z = z0; z < z1; ++z) {
    // Lattice layer z + 1 is new; its plane held layer z - 1, which no later quad touches.
    planes.Reset((z + 1) & 1);
    std::vector<int64_t>* list = &scanned;
    if (layers != nullptr) {
      list = &(*layers)[static_cast<size_t>(z)];
    } else {
      scanned.clear();
      BoundaryVoxelsOfLayer(grid, z, scanned);
    }
    for (const int64_t i : *list) {
      const int x = static_cast<int>(i % row), y = static_cast<int>(i % plane / row);
      const Coord s{x, y, z};
      for (int a = 0; a < 3; ++a)
        for (int positive = 0; positive < 2; ++positive) {
          const int64_t n = i + (positive ? st[a] : -st[a]);
          if (!IsOutside(states[n])) continue;
          VoxelBoundary::Quad quad;
          quad.solid = s;
          quad.axis = static_cast<int8_t>(a);
          quad.positive = positive != 0;
          const int u = (a + 1) % 3, v = (a + 2) % 3;
          const std::array<Coord, 4> corner_coords = QuadCornerCoords(quad);
          std::array<CornerEntry, 4> entries;
          for (int k = 0; k < 4; ++k) {
            const Coord& c = corner_coords[k];
            const CornerEntry e = corner_entry(c);
            entries[k] = e;
            std::array<int, 3> bits{};
            bits[u] = s[u] - c[u] + 1;
            bits[v] = s[v] - c[v] + 1;
            const int fan = table[e.config].quad_fan[QuadIndex(a, bits)];
            quad.corners[k] = e.base >= 0 ? e.base + fan : -1 - (8 * (-2 - e.base) + fan);
          }
          Coord outside = s;
          outside[a] += positive ? 1 : -1;
          for (int k = 0; k < 4; ++k) {
            const int k1 = (k + 1) % 4;
            const Coord& c0 = corner_coords[k];
            const Coord& c1 = corner_coords[k1];
            const int w = c0[u] != c1[u] ? u : v;
            const int up = c1[w] > c0[w] ? 1 : 0;
            const int h0 = 2 * w + up, h1 = 2 * w + (1 - up);
            const CornerFacts& f0 = table[entries[k].config];
            const CornerFacts& f1 = table[entries[k1].config];
            if (!((f0.ambiguous_one_fan >> h0) & 1) || !((f1.ambiguous_one_fan >> h1) & 1))
              continue;
            const Coord& lower = up ? c0 : c1;
            const MidpointKey key{grid.Index(lower) * 3 + w, grid.Index(outside)};
            auto [it, inserted] = midpoint_ids.try_emplace(key);
            if (inserted) {
              if (below && w != 2 && lower.z == z0) {
                // An edge in lattice plane z0: the pair's other quad is in the layer below
                // (the two solid voxels of a diagonal pattern lie on either side of the
                // plane), which made the midpoint.
                it->second = -2 - static_cast<int32_t>(out.below_midpoints.size());
                out.below_midpoints.push_back(key);
              } else {
                // Provisional: index into `midpoints`; shifted past the fan vertices at the
                // end.
                it->second = static_cast<int32_t>(out.midpoints.size());
                VoxelBoundary::EdgeMidpoint m;
                m.ends = up ? std::array<int32_t, 2>{quad.corners[k], quad.corners[k1]}
                            : std::array<int32_t, 2>{quad.corners[k1], quad.corners[k]};
                m.edge_start = lower;
                m.axis = w;
                m.outside = outside;
                out.midpoints.push_back(m);
              }
            }
            quad.midpoints[k] = it->second;
          }
          out.quads.push_back(quad);
        }
    }
    if (layers != nullptr) std::vector<int64_t>().swap(*list);  // done with: freed
  }
  // What the slab above takes from this one.
  const int top = z1 & 1;
  for (int64_t at : planes.made[top])
    out.top_corners.emplace_back(at, planes.corners[top][at].base);
  std::sort(out.top_corners.begin(), out.top_corners.end());
  for (size_t m = 0; m < out.midpoints.size(); ++m) {
    const auto& mid = out.midpoints[m];
    if (mid.axis == 2 || mid.edge_start.z != z1) continue;
    out.top_midpoints.push_back(
        {{grid.Index(mid.edge_start) * 3 + mid.axis, grid.Index(mid.outside)},
         static_cast<int32_t>(m)});
  }
  std::sort(out.top_midpoints.begin(), out.top_midpoints.end());
  planes.Reset(0);
  planes.Reset(1);
}

// Slabs of at least this many voxel layers.
constexpr int kMinSlabLayers = 8;

// The slabs' boundaries joined in slab order, their ids made global: the one-thread pass's
// numbering, since each slab numbers what it makes in that pass's order and the pass makes
// everything of a slab before anything of the next.
VoxelBoundary JoinSlabs(std::vector<SlabBoundary>& parts, int threads) {
  const size_t n = parts.size();
  std::vector<int64_t> fan_at(n + 1, 0), mid_at(n + 1, 0), quad_at(n + 1, 0);
  VoxelBoundary out;
  for (size_t k = 0; k < n; ++k) {
    fan_at[k + 1] = fan_at[k] + static_cast<int64_t>(parts[k].fan_vertices.size());
    mid_at[k + 1] = mid_at[k] + static_cast<int64_t>(parts[k].midpoints.size());
    quad_at[k + 1] = quad_at[k] + static_cast<int64_t>(parts[k].quads.size());
    out.corner_contacts += parts[k].corner_contacts;
  }
  const int32_t nfan = static_cast<int32_t>(fan_at[n]);
  out.fan_vertices.resize(static_cast<size_t>(fan_at[n]));
  out.midpoints.resize(static_cast<size_t>(mid_at[n]));
  out.quads.resize(static_cast<size_t>(quad_at[n]));
  RunTasks(threads, static_cast<int64_t>(n), [&](int, int64_t task) {
    const size_t k = static_cast<size_t>(task);
    SlabBoundary& part = parts[k];
    // The global first fan vertex of each corner taken from the slab below, and the global id
    // of each midpoint taken from it.
    std::vector<int32_t> below_corner(part.below_corners.size());
    for (size_t j = 0; j < part.below_corners.size(); ++j) {
      const auto& top = parts[k - 1].top_corners;
      const auto it = std::lower_bound(top.begin(), top.end(),
                                       std::pair<int64_t, int32_t>{part.below_corners[j],
                                                                   INT32_MIN});
      below_corner[j] = static_cast<int32_t>(fan_at[k - 1]) + it->second;
    }
    std::vector<int32_t> below_midpoint(part.below_midpoints.size());
    for (size_t j = 0; j < part.below_midpoints.size(); ++j) {
      const auto& top = parts[k - 1].top_midpoints;
      const auto it = std::lower_bound(
          top.begin(), top.end(),
          std::pair<MidpointKey, int32_t>{part.below_midpoints[j], INT32_MIN});
      below_midpoint[j] = nfan + static_cast<int32_t>(mid_at[k - 1]) + it->second;
    }
    const int32_t fan0 = static_cast<int32_t>(fan_at[k]);
    const int32_t mid0 = nfan + static_cast<int32_t>(mid_at[k]);
    auto corner_id = [&](int32_t id) {
      if (id >= 0) return fan0 + id;
      const int32_t code = -1 - id;
      return below_corner[static_cast<size_t>(code >> 3)] + (code & 7);
    };
    std::copy(part.fan_vertices.begin(), part.fan_vertices.end(),
              out.fan_vertices.begin() + fan_at[k]);
    for (size_t j = 0; j < part.midpoints.size(); ++j) {
      VoxelBoundary::EdgeMidpoint m = part.midpoints[j];
      for (int32_t& e : m.ends) e = corner_id(e);
      out.midpoints[static_cast<size_t>(mid_at[k]) + j] = m;
    }
    for (size_t j = 0; j < part.quads.size(); ++j) {
      VoxelBoundary::Quad q = part.quads[j];
      for (int32_t& c : q.corners) c = corner_id(c);
      for (int32_t& m : q.midpoints)
        if (m >= 0)
          m += mid0;
        else if (m <= -2)
          m = below_midpoint[static_cast<size_t>(-2 - m)];
      out.quads[static_cast<size_t>(quad_at[k]) + j] = q;
    }
    // Done with: freed (the top lists stay for the slab above).
    BoundaryArray<VoxelBoundary::FanVertex>().swap(part.fan_vertices);
    BoundaryArray<VoxelBoundary::EdgeMidpoint>().swap(part.midpoints);
    BoundaryArray<VoxelBoundary::Quad>().swap(part.quads);
  });
  return out;
}

VoxelBoundary ExtractOnSlabs(const VoxelGrid& grid, int threads, int slabs) {
  const int layers = std::max(grid.dim(2) - 2, 0);
  slabs = std::clamp(slabs, 1, std::max(layers, 1));
  std::vector<SlabBoundary> parts(static_cast<size_t>(slabs));
  std::vector<CornerPlanes> planes(static_cast<size_t>(std::max(threads, 1)));
  RunTasks(threads, slabs, [&](int worker, int64_t s) {
    const int z0 = 1 + static_cast<int>(s * layers / slabs);
    const int z1 = 1 + static_cast<int>((s + 1) * layers / slabs);
    BuildSlab(grid, z0, z1, nullptr, planes[static_cast<size_t>(worker)],
              parts[static_cast<size_t>(s)]);
  });
  std::vector<CornerPlanes>().swap(planes);
  return JoinSlabs(parts, threads);
}

}  // namespace

std::array<Coord, 4> QuadCornerCoords(const VoxelBoundary::Quad& quad) {
  // Axis a, then u = a + 1 and v = a + 2 (mod 3) take the two offsets. Spelled out per axis:
  // Coord's run-time operator[] kept the corners in memory, a quarter of Cuberille's time.
  const auto& offsets = quad.positive ? kPositiveOffsets : kNegativeOffsets;
  const int lift = quad.positive ? 1 : 0;
  const Coord s = quad.solid;
  std::array<Coord, 4> corners;
  for (int k = 0; k < 4; ++k) {
    const int du = offsets[k][0], dv = offsets[k][1];
    switch (quad.axis) {
      case 0: corners[k] = {s.x + lift, s.y + du, s.z + dv}; break;
      case 1: corners[k] = {s.x + dv, s.y + lift, s.z + du}; break;
      default: corners[k] = {s.x + du, s.y + dv, s.z + lift}; break;
    }
  }
  return corners;
}

int NumFans(int config) { return Table()[config].num_fans; }
bool IsCornerContact(int config) {
  // Exactly two solid octants, opposite through the corner (std::popcount is a library call
  // on the baseline x86-64 target, 4% of Cuberille).
  return config == 0x81 || config == 0x42 || config == 0x24 || config == 0x18;
}
Vec3d FanCentroid(int config, int fan) { return Table()[config].centroid[fan]; }
Vec3d FanOutsideDirection(int config, int fan) { return Table()[config].outside_direction[fan]; }
int FanSolidOctant(int config, int fan) { return Table()[config].solid_octant[fan]; }

VoxelBoundary ExtractVoxelBoundary(const VoxelGrid& grid, int threads) {
  if (threads > 1 && grid.size() >= kMinSplitGridVoxels && grid.dim(2) >= 2 * kMinSlabLayers) {
    // Many slabs a thread: the boundary is not spread evenly over the layers.
    return ExtractOnSlabs(grid, threads, std::min(grid.dim(2) / kMinSlabLayers, 16 * threads));
  }
  // The voxels with a boundary face, found on the threads; their quads are made here in index
  // order.
  std::vector<std::vector<int64_t>> layers = BoundaryVoxelsByLayer(grid, threads);
  SlabBoundary part;
  CornerPlanes planes;
  BuildSlab(grid, 1, std::max(grid.dim(2) - 1, 1), &layers, planes, part);
  VoxelBoundary out;
  out.fan_vertices = std::move(part.fan_vertices);
  out.midpoints = std::move(part.midpoints);
  out.quads = std::move(part.quads);
  out.corner_contacts = part.corner_contacts;
  // Corners found after a midpoint still add fan vertices, so midpoint ids are final only now.
  const int32_t nfan = static_cast<int32_t>(out.fan_vertices.size());
  for (auto& quad : out.quads)
    for (int32_t& m : quad.midpoints)
      if (m >= 0) m += nfan;
  return out;
}

VoxelBoundary ExtractVoxelBoundaryOnSlabs(const VoxelGrid& grid, int threads, int slabs) {
  return ExtractOnSlabs(grid, threads, slabs);
}

}  // namespace membrane

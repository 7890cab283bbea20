#include "core/mesh/morton_order.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/base/parallel_tasks.h"
#include "core/base/split_sort.h"
#include "core/engine/arena_allocator.h"

namespace membrane {
namespace {

template <typename T>
using Unfilled = std::vector<T, UnfilledAllocator<T>>;

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

// A vertex's Morton code beside its index: the sort compares contiguous items instead of
// looking the codes up through the indices (half the sort's time). A trivial type, so that its
// arrays are left unset when made (std::pair's constructor zeroes its members: a serial pass
// over the keys and again over the merge's buffer). Ordered as the pair (code, vertex).
struct MortonKey {
  uint64_t code;
  int32_t vertex;
  friend bool operator<(const MortonKey& a, const MortonKey& b) {
    return a.code != b.code ? a.code < b.code : a.vertex < b.vertex;
  }
};

}  // namespace

void MortonOrder(TriangleMesh& mesh, double cell, std::vector<Point3f>* companion,
                 int threads) {
  const size_t nv = mesh.vertices.size();
  if (nv == 0) return;
  const size_t nf = mesh.faces.size();
  // The loops below run on ranges on the threads when the mesh is large; every range writes
  // its own items, so the result does not depend on the split.
  const bool split = threads > 1 && nv >= kMinSplitItems;
  const int64_t ranges = split ? 4 * int64_t{threads} : 1;
  // The face sort counts per range of faces in an array of nv counts: one range a thread.
  const int64_t face_ranges = split ? threads : 1;
  auto for_ranges = [&](size_t n, int64_t parts, auto body) {
    RunTasks(threads, parts, [&](int, int64_t r) {
      body(static_cast<size_t>(r), static_cast<size_t>(r * static_cast<int64_t>(n) / parts),
           static_cast<size_t>((r + 1) * static_cast<int64_t>(n) / parts));
    });
  };
  std::vector<std::array<float, 3>> range_lo(static_cast<size_t>(ranges), mesh.vertices[0]);
  for_ranges(nv, ranges, [&](size_t r, size_t begin, size_t end) {
    std::array<float, 3>& lo = range_lo[r];
    for (size_t v = begin; v < end; ++v)
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], mesh.vertices[v][k]);
  });
  std::array<float, 3> lo = mesh.vertices[0];
  for (const auto& l : range_lo)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], l[k]);
  // Unique (code, vertex) keys, so the order is the same however the sort is split; made on the
  // halves' threads.
  Unfilled<MortonKey> keyed(nv);
  MakeAndSortUnique(keyed, threads, [&](size_t v) {
    uint64_t code = 0;
    for (int k = 0; k < 3; ++k) {
      const double c = std::floor((mesh.vertices[v][k] - lo[k]) / cell);
      code |= Spread(static_cast<uint64_t>(std::clamp(c, 0.0, double(0x1fffff)))) << k;
    }
    return MortonKey{code, static_cast<int32_t>(v)};
  });
  // The mesh's arrays are rewritten in place from copies: the copies' fresh pages are
  // first written on the ranges, where new arrays of the mesh's own type would be filled (and
  // their pages faulted) on the calling thread.
  Unfilled<int32_t> new_id(nv);
  Unfilled<Point3f> old_vertices(nv);
  Unfilled<Point3f> old_companion(companion != nullptr ? nv : 0);
  for_ranges(nv, ranges, [&](size_t, size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      old_vertices[i] = mesh.vertices[i];
      if (companion != nullptr) old_companion[i] = (*companion)[i];
    }
  });
  for_ranges(nv, ranges, [&](size_t, size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const int32_t old = keyed[i].vertex;
      new_id[old] = static_cast<int32_t>(i);
      mesh.vertices[i] = old_vertices[old];
      if (companion != nullptr) (*companion)[i] = old_companion[old];
    }
  });
  Unfilled<MortonKey>().swap(keyed);
  // Faces by their lowest new vertex, stably: a counting sort, linear where a comparison sort
  // of the faces would take a tenth of the surface nets. Each range of faces counts in its own
  // array; a face's place is the faces of lower vertices, then those of its vertex in earlier
  // ranges, then those before it in its range: the one-range order.
  std::vector<std::vector<int32_t>> count(static_cast<size_t>(face_ranges));
  Unfilled<std::array<int32_t, 3>> old_faces(nf);
  for_ranges(nf, face_ranges, [&](size_t r, size_t begin, size_t end) {
    std::vector<int32_t>& c = count[r];
    c.assign(nv, 0);
    for (size_t i = begin; i < end; ++i) {
      auto& f = old_faces[i];
      for (int k = 0; k < 3; ++k) f[k] = new_id[mesh.faces[i][k]];
      ++c[std::min({f[0], f[1], f[2]})];
    }
  });
  // Each range of vertices turns the counts into places from its own sums' prefix.
  std::vector<int64_t> vertex_range_faces(static_cast<size_t>(ranges) + 1, 0);
  for_ranges(nv, ranges, [&](size_t r, size_t begin, size_t end) {
    int64_t sum = 0;
    for (const auto& c : count)
      for (size_t v = begin; v < end; ++v) sum += c[v];
    vertex_range_faces[r + 1] = sum;
  });
  for (int64_t r = 0; r < ranges; ++r) vertex_range_faces[r + 1] += vertex_range_faces[r];
  for_ranges(nv, ranges, [&](size_t r, size_t begin, size_t end) {
    int64_t next = vertex_range_faces[r];
    for (size_t v = begin; v < end; ++v)
      for (auto& c : count) {
        const int32_t here = c[v];
        c[v] = static_cast<int32_t>(next);
        next += here;
      }
  });
  for_ranges(nf, face_ranges, [&](size_t r, size_t begin, size_t end) {
    std::vector<int32_t>& c = count[r];
    for (size_t i = begin; i < end; ++i) {
      const auto& f = old_faces[i];
      mesh.faces[static_cast<size_t>(c[std::min({f[0], f[1], f[2]})]++)] = f;
    }
  });
}

}  // namespace membrane

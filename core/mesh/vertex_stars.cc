#include "core/mesh/vertex_stars.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/base/parallel_tasks.h"

namespace membrane {

VertexStars FacesAroundVertices(const std::vector<std::array<int32_t, 3>>& faces,
                                int32_t num_vertices, int threads) {
  const int64_t nv = num_vertices;
  const int64_t nf = static_cast<int64_t>(faces.size());
  const bool split = threads > 1 && nv >= (int64_t{1} << 16);
  // An array of nv counts a range of faces: one range a thread. Vertex ranges are cheap and
  // unequal in work where the counts are: four a thread.
  const int64_t face_ranges = split ? threads : 1;
  const int64_t vertex_ranges = split ? 4 * int64_t{threads} : 1;
  auto range = [](int64_t n, int64_t parts, int64_t r) {
    return std::array<int64_t, 2>{r * n / parts, (r + 1) * n / parts};
  };
  std::vector<std::vector<int32_t>> count(static_cast<size_t>(face_ranges));
  RunTasks(threads, face_ranges, [&](int, int64_t r) {
    std::vector<int32_t>& c = count[static_cast<size_t>(r)];
    c.assign(static_cast<size_t>(nv), 0);
    const auto [begin, end] = range(nf, face_ranges, r);
    for (int64_t f = begin; f < end; ++f)
      for (int32_t v : faces[static_cast<size_t>(f)]) ++c[static_cast<size_t>(v)];
  });
  std::vector<int64_t> first(static_cast<size_t>(vertex_ranges) + 1, 0);
  RunTasks(threads, vertex_ranges, [&](int, int64_t r) {
    const auto [begin, end] = range(nv, vertex_ranges, r);
    int64_t sum = 0;
    for (const auto& c : count)
      for (int64_t v = begin; v < end; ++v) sum += c[static_cast<size_t>(v)];
    first[static_cast<size_t>(r) + 1] = sum;
  });
  for (size_t r = 0; r + 1 < first.size(); ++r) first[r + 1] += first[r];
  VertexStars stars;
  stars.start.resize(static_cast<size_t>(nv) + 1);
  stars.faces.resize(static_cast<size_t>(first.back()));
  // Each count becomes the place of its range's first face of that vertex.
  RunTasks(threads, vertex_ranges, [&](int, int64_t r) {
    const auto [begin, end] = range(nv, vertex_ranges, r);
    int64_t next = first[static_cast<size_t>(r)];
    for (int64_t v = begin; v < end; ++v) {
      stars.start[static_cast<size_t>(v)] = static_cast<int32_t>(next);
      for (auto& c : count) {
        const int32_t here = c[static_cast<size_t>(v)];
        c[static_cast<size_t>(v)] = static_cast<int32_t>(next);
        next += here;
      }
    }
  });
  stars.start[static_cast<size_t>(nv)] = static_cast<int32_t>(first.back());
  RunTasks(threads, face_ranges, [&](int, int64_t r) {
    std::vector<int32_t>& c = count[static_cast<size_t>(r)];
    const auto [begin, end] = range(nf, face_ranges, r);
    for (int64_t f = begin; f < end; ++f)
      for (int32_t v : faces[static_cast<size_t>(f)])
        stars.faces[static_cast<size_t>(c[static_cast<size_t>(v)]++)] = static_cast<int32_t>(f);
  });
  return stars;
}

}  // namespace membrane

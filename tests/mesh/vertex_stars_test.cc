#include "core/mesh/vertex_stars.h"

#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "gtest/gtest.h"

namespace membrane {
namespace {

TEST(VertexStars, ListEachVertexsFacesInOrderOnAnyThreadCount) {
  // Random faces over few and many vertices (2^16 and more: the ranges on the threads), some
  // vertices unused, against the faces read vertex by vertex.
  std::mt19937 rng(5);
  for (int32_t nv : {1, 7, 300, 70000, 150000}) {
    std::uniform_int_distribution<int32_t> vertex(0, nv - 1);
    std::vector<std::array<int32_t, 3>> faces(static_cast<size_t>(nv) * 2 + 3);
    for (auto& f : faces) f = {vertex(rng), vertex(rng), vertex(rng)};
    std::vector<std::vector<int32_t>> expected(static_cast<size_t>(nv));
    for (size_t f = 0; f < faces.size(); ++f)
      for (int32_t v : faces[f])
        expected[static_cast<size_t>(v)].push_back(static_cast<int32_t>(f));
    for (int threads : {1, 2, 3}) {
      const VertexStars stars = FacesAroundVertices(faces, nv, threads);
      ASSERT_EQ(stars.start.size(), static_cast<size_t>(nv) + 1);
      ASSERT_EQ(stars.faces.size(), 3 * faces.size());
      EXPECT_EQ(stars.start[0], 0);
      for (int32_t v = 0; v < nv; ++v) {
        const std::vector<int32_t> got(stars.faces.begin() + stars.start[v],
                                       stars.faces.begin() + stars.start[v + 1]);
        ASSERT_EQ(got, expected[static_cast<size_t>(v)])
            << nv << " vertices, vertex " << v << ", " << threads << " threads";
      }
    }
  }
}

}  // namespace
}  // namespace membrane

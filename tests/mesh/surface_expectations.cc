#include "tests/mesh/surface_expectations.h"

#include <algorithm>
#include <string>
#include <utility>

#include "gtest/gtest.h"

namespace membrane::testing {

void ExpectValidSurface(const TriangleMesh& mesh, int shells, std::vector<int> genus) {
  ExpectValidReport(CheckMesh(mesh), shells, std::move(genus));
}

void ExpectValidReport(const MeshReport& r, int shells, std::vector<int> genus) {
  const std::string json = MeshReportToJson(r);
  EXPECT_TRUE(r.closed) << json;
  EXPECT_TRUE(r.manifold) << json;
  EXPECT_TRUE(r.oriented) << json;
  EXPECT_TRUE(r.positive_volume) << json;
  EXPECT_EQ(r.self_intersections, 0) << json;
  EXPECT_EQ(r.degenerate_faces, 0) << json;
  EXPECT_EQ(r.shells, shells) << json;
  std::vector<int> g = r.genus;
  std::sort(g.begin(), g.end());
  std::sort(genus.begin(), genus.end());
  EXPECT_EQ(g, genus) << json;
}

}  // namespace membrane::testing

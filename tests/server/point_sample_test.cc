// The sample of a job's input points that the web console draws over its mesh.
#include "server/point_sample.h"

#include <cstring>

#include <gtest/gtest.h>

namespace membrane::server {
namespace {

Point3f At(const std::string& sample, size_t i) {
  Point3f p;
  std::memcpy(p.data(), sample.data() + i * sizeof(Point3f), sizeof(Point3f));
  return p;
}

TEST(PointSample, KeepsEveryPointOfASmallCloud) {
  PointCloud cloud;
  for (int i = 0; i < 100; ++i) cloud.points.push_back({float(i), float(2 * i), -float(i)});
  const std::string sample = SamplePoints(cloud);
  ASSERT_EQ(sample.size(), 100 * sizeof(Point3f));
  for (int i = 0; i < 100; ++i) EXPECT_EQ(At(sample, i), cloud.points[i]);
}

TEST(PointSample, SpreadsOverTheWholeOfALargeCloud) {
  PointCloud cloud;
  for (int i = 0; i < 50'000; ++i) cloud.points.push_back({float(i), 0, 0});
  const std::string sample = SamplePoints(cloud);
  ASSERT_EQ(sample.size(), kMaxSamplePoints * sizeof(Point3f));
  EXPECT_EQ(At(sample, 0)[0], 0);
  // Point i of the sample is point i * 50000 / 20000 = 2.5 i of the cloud, rounded down.
  EXPECT_EQ(At(sample, 1)[0], 2);
  EXPECT_EQ(At(sample, 2)[0], 5);
  EXPECT_EQ(At(sample, kMaxSamplePoints - 1)[0], 49'997);
  EXPECT_TRUE(SamplePoints(PointCloud{}).empty());
}

}  // namespace
}  // namespace membrane::server

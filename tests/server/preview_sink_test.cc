// PreviewSink (server/preview_sink.h): the preview is drawn beside the inner sink's write and
// kept only when the inner sink took the mesh.
#include "server/preview_sink.h"

#include <string>

#include <gtest/gtest.h>

#include "absl/status/status.h"
#include "core/geometry/position_grid.h"
#include "tests/mesh/mesh_builders.h"

namespace membrane::server {
namespace {

// A sink that counts the faces it was given and answers with `status`.
class CountingSink : public MeshSink {
 public:
  explicit CountingSink(absl::Status status) : status_(std::move(status)) {}
  absl::Status Write(const TriangleMesh& mesh, const PositionGrid& /*grid*/) override {
    faces_ += mesh.faces.size();
    return status_;
  }
  size_t faces() const { return faces_; }

 private:
  absl::Status status_;
  size_t faces_ = 0;
};

TEST(PreviewSink, KeepsAPictureOfTheMeshTheInnerSinkTook) {
  const TriangleMesh torus = testing::TorusMesh(48, 24, 1.0f, 0.3f);
  CountingSink inner(absl::OkStatus());
  PreviewSink sink(inner);
  ASSERT_TRUE(sink.Write(torus, BoundingGrid(torus.vertices, 16)).ok());
  EXPECT_EQ(inner.faces(), torus.faces.size());
  const std::string png = sink.TakePng();
  ASSERT_FALSE(png.empty());
  EXPECT_EQ(png.substr(1, 3), "PNG");
  const absl::StatusOr<std::string> alone = PreviewPng(torus);
  ASSERT_TRUE(alone.ok()) << alone.status();
  EXPECT_EQ(png, *alone);  // the same picture as drawn on the calling thread
}

TEST(PreviewSink, ReturnsTheInnerSinksErrorAndKeepsNoPicture) {
  const TriangleMesh torus = testing::TorusMesh(48, 24, 1.0f, 0.3f);
  CountingSink inner(absl::ResourceExhaustedError("the mesh is over the result limit"));
  PreviewSink sink(inner);
  const absl::Status written = sink.Write(torus, BoundingGrid(torus.vertices, 16));
  EXPECT_EQ(written.code(), absl::StatusCode::kResourceExhausted);
  EXPECT_EQ(written.message(), "the mesh is over the result limit");
  EXPECT_TRUE(sink.TakePng().empty());
}

}  // namespace
}  // namespace membrane::server

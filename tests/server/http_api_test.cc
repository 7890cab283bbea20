// membraned --http-listen: the web console's JSON API and files, in process, over real HTTP
// requests: the same jobs, tokens and visibility as the gRPC calls.
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "core/io/draco_codec.h"
#include "core/io/mesh_io.h"
#include "core/render/mesh_views.h"
#include "core/render/png_codec.h"
#include "server/preview_sink.h"
#include "tests/server/http_get.h"
#include "tests/server/service_fixture.h"
#include "tests/support/scratch_dir.h"

namespace membrane::testing {
namespace {

// `png` is a preview of a mesh: 3 views of kPreviewViewPixels, each drawn over a fifth to
// nine tenths of its pixels (the mesh fills 90% of the largest side), background at the corners.
void ExpectPreview(const std::string& png) {
  const absl::StatusOr<RgbImage> image = DecodePng(png);
  ASSERT_TRUE(image.ok()) << image.status();
  const int n = server::kPreviewViewPixels;
  ASSERT_EQ(image->width, 3 * n);
  ASSERT_EQ(image->height, n);
  const uint32_t background = MeshViewOptions().background;
  for (int v = 0; v < 3; ++v) {
    int drawn = 0;
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) drawn += image->At(v * n + x, y) != background;
    }
    EXPECT_GT(drawn, n * n / 5) << "view " << v;
    EXPECT_LT(drawn, n * n * 9 / 10) << "view " << v;
    EXPECT_EQ(image->At(v * n, 0), background) << "view " << v;
  }
}

class HttpApiTest : public ServiceTest {
 protected:
  HttpApiTest() {
    options_.http_listen = "127.0.0.1:0";
    options_.web_dir = MEMBRANE_SOURCE_DIR "/server/web";
  }
  // Tokens of two clients and an operator.
  void UseTokens() {
    options_.clients = {{"alice", "tok-alice"}, {"bob", "tok-bob"}, {"ops", "tok-ops", true}};
  }
  HttpReply Get(const std::string& path, const std::string& token = "") {
    return HttpCall(server_->http_port(), "GET", path, token.empty() ? "" : "Bearer " + token);
  }
  HttpReply Post(const std::string& path, const std::string& token = "") {
    return HttpCall(server_->http_port(), "POST", path, token.empty() ? "" : "Bearer " + token);
  }
};

TEST_F(HttpApiTest, OffByDefault) {
  options_.http_listen.clear();
  StartServer();
  EXPECT_EQ(server_->http_port(), 0);
}

TEST_F(HttpApiTest, ServesThePageAndThreeJsFromInstalledFiles) {
  StartServer();
  ASSERT_GT(server_->http_port(), 0);
  const HttpReply page = Get("/");
  EXPECT_EQ(page.status, 200);
  EXPECT_TRUE(absl::StrContains(page.headers, "Content-Type: text/html")) << page.headers;
  EXPECT_TRUE(absl::StrContains(page.body, "/console.js"));
  // three.js is asked for by the console's script when it first shows a mesh.
  EXPECT_TRUE(absl::StrContains(Get("/console.js").body, "/three/three.min.js"));
  EXPECT_TRUE(absl::StrContains(page.headers, "Content-Security-Policy: default-src 'self';"))
      << page.headers;
  const HttpReply three = Get("/three/three.min.js");
  EXPECT_EQ(three.status, 200);
  EXPECT_GT(three.body.size(), 100000u);
  EXPECT_EQ(Get("/three/OrbitControls.js").status, 200);
  EXPECT_EQ(Get("/console.js").status, 200);
  EXPECT_EQ(Get("/../server/main.cc").status, 404);
  EXPECT_EQ(Get("/etc/passwd").status, 404);
  EXPECT_EQ(Post("/").status, 405);
}

TEST_F(HttpApiTest, StartFailsNamingAMissingWebDirectory) {
  options_.web_dir = "/nonexistent/web";
  server_ = std::make_unique<server::MembraneServer>(options_, &clock_);
  const absl::StatusOr<int> port = server_->Start("127.0.0.1:0");
  ASSERT_FALSE(port.ok());
  EXPECT_TRUE(absl::StrContains(port.status().message(), "/nonexistent/web")) << port.status();
  EXPECT_TRUE(absl::StrContains(port.status().message(), "--web-dir")) << port.status();
}

TEST_F(HttpApiTest, TokensAreCheckedAsForGrpc) {
  UseTokens();
  StartServer();
  // The page itself is open: it asks for the token.
  EXPECT_EQ(Get("/").status, 200);
  const HttpReply none = Get("/api/jobs");
  EXPECT_EQ(none.status, 401);
  EXPECT_TRUE(absl::StrContains(none.headers, "WWW-Authenticate: Bearer")) << none.headers;
  EXPECT_TRUE(absl::StrContains(none.body, "\"UNAUTHENTICATED\"")) << none.body;
  EXPECT_EQ(Get("/api/jobs", "tok-mallory").status, 401);
  EXPECT_EQ(HttpCall(server_->http_port(), "GET", "/api/jobs", "tok-alice").status, 401);
  const HttpReply alice = Get("/api/jobs", "tok-alice");
  EXPECT_EQ(alice.status, 200);
  EXPECT_EQ(alice.body, "{\"jobs\":[]}");
}

TEST_F(HttpApiTest, AJobIsSeenFetchedAndCancelledOnlyByItsClientAndOperators) {
  UseTokens();
  StartServer();
  token_ = "tok-alice";
  const CallResult done = Reconstruct(DracoCloud("sphere", 5000), {});
  ASSERT_EQ(done.FinalState(), v1::SUCCEEDED) << done.status.error_message();
  const std::string id = done.JobId();
  const std::string job = "/api/jobs/" + id;

  const HttpReply mine = Get(job, "tok-alice");
  ASSERT_EQ(mine.status, 200) << mine.body;
  EXPECT_TRUE(absl::StrContains(mine.body, "\"state\":\"SUCCEEDED\"")) << mine.body;
  EXPECT_TRUE(absl::StrContains(mine.body, "\"client\":\"alice\"")) << mine.body;
  EXPECT_TRUE(absl::StrContains(mine.body, "\"statistics\":{")) << mine.body;
  EXPECT_TRUE(absl::StrContains(Get("/api/jobs", "tok-alice").body, id));
  EXPECT_TRUE(absl::StrContains(Get("/api/jobs", "tok-ops").body, id));
  EXPECT_FALSE(absl::StrContains(Get("/api/jobs", "tok-bob").body, id));

  // Bob learns nothing of Alice's job: the 404 of an unknown id, for every path of it.
  for (const std::string path : {"", "/events", "/mesh.drc", "/mesh.ply", "/preview.png"}) {
    const HttpReply theirs = Get(job + path, "tok-bob");
    EXPECT_EQ(theirs.status, 404) << path;
    EXPECT_TRUE(absl::StrContains(theirs.body, "no job '" + id + "' (unknown, or its result expired)"))
        << path << " " << theirs.body;
  }
  EXPECT_EQ(Post(job + "/cancel", "tok-bob").status, 404);
  EXPECT_EQ(Get(job, "tok-ops").status, 200);
}

TEST_F(HttpApiTest, EventsMeshesAndPreviewOfAFinishedJob) {
  StartServer();
  const CallResult done = Reconstruct(DracoCloud("torus", 20000), {});
  ASSERT_EQ(done.FinalState(), v1::SUCCEEDED) << done.status.error_message();
  const std::string job = "/api/jobs/" + done.JobId();

  const HttpReply events = Get(job + "/events?after=0&wait=5");
  ASSERT_EQ(events.status, 200);
  EXPECT_TRUE(absl::StrContains(events.body, "\"generation\":{\"generation\":1,")) << events.body;
  EXPECT_TRUE(absl::StrContains(events.body, "\"stage\":\"encode\"")) << events.body;
  EXPECT_TRUE(absl::StrContains(events.body, "\"done\":true")) << events.body;
  // Past the last event of a finished job, the answer comes at once, empty.
  const size_t at = events.body.find("\"next\":");
  ASSERT_NE(at, std::string::npos);
  const std::string next = events.body.substr(at + 7, events.body.find(',', at) - at - 7);
  const absl::Time asked = absl::Now();
  const HttpReply rest = Get(job + "/events?after=" + next + "&wait=20");
  EXPECT_LT(absl::Now() - asked, absl::Seconds(10));
  EXPECT_TRUE(absl::StartsWith(rest.body, "{\"events\":[],")) << rest.body;
  EXPECT_EQ(Get(job + "/events?after=-1").status, 400);
  EXPECT_EQ(Get(job + "/events?wait=soon").status, 400);

  // The Draco download is the mesh the gRPC call delivered; the PLY one holds the same mesh.
  const HttpReply drc = Get(job + "/mesh.drc");
  ASSERT_EQ(drc.status, 200);
  EXPECT_EQ(drc.body, done.Mesh());
  EXPECT_TRUE(absl::StrContains(drc.headers, "attachment; filename=\"" + done.JobId() + ".drc\""));
  const HttpReply ply = Get(job + "/mesh.ply");
  ASSERT_EQ(ply.status, 200);
  const absl::StatusOr<TriangleMesh> from_ply = ReadMeshFromBuffer(ply.body, FileFormat::kPly);
  const absl::StatusOr<TriangleMesh> from_drc = DecodeDracoMesh(drc.body);
  ASSERT_TRUE(from_ply.ok()) << from_ply.status();
  ASSERT_TRUE(from_drc.ok()) << from_drc.status();
  EXPECT_EQ(from_ply->faces.size(), from_drc->faces.size());
  EXPECT_EQ(from_ply->vertices.size(), from_drc->vertices.size());

  // The preview: three views of the torus.
  const HttpReply preview = Get(job + "/preview.png");
  ASSERT_EQ(preview.status, 200);
  EXPECT_TRUE(absl::StrContains(preview.headers, "Content-Type: image/png"));
  ExpectPreview(preview.body);
  EXPECT_TRUE(absl::StrContains(Get("/api/jobs").body, "\"has_preview\":true"));

  // The sample of the input points: all 20000 of them, float32 x y z, near the torus.
  const HttpReply points = Get(job + "/points");
  ASSERT_EQ(points.status, 200);
  EXPECT_EQ(points.body.size(), 20000u * 12);
  EXPECT_TRUE(absl::StrContains(Get(job).body, "\"sample_points\":20000")) << Get(job).body;

  EXPECT_EQ(Get(job + "/nothing").status, 404);
  EXPECT_EQ(Post(job + "/mesh.drc").status, 405);
  EXPECT_EQ(Get(job + "/cancel").status, 405);
}

TEST_F(HttpApiTest, APlyJobsMeshDownloadsAsDracoToo) {
  StartServer();
  v1::Parameters p;
  p.set_mesh_format(v1::MESH_FORMAT_PLY);
  const CallResult done = Reconstruct(DracoCloud("sphere", 5000), p);
  ASSERT_EQ(done.FinalState(), v1::SUCCEEDED) << done.status.error_message();
  const std::string job = "/api/jobs/" + done.JobId();
  EXPECT_EQ(Get(job + "/mesh.ply").body, done.Mesh());
  const absl::StatusOr<TriangleMesh> from_drc = DecodeDracoMesh(Get(job + "/mesh.drc").body);
  const absl::StatusOr<TriangleMesh> from_ply = ReadMeshFromBuffer(done.Mesh(), FileFormat::kPly);
  ASSERT_TRUE(from_drc.ok()) << from_drc.status();
  ASSERT_TRUE(from_ply.ok()) << from_ply.status();
  EXPECT_EQ(from_drc->faces.size(), from_ply->faces.size());
}

TEST_F(HttpApiTest, AJobRestoredFromTheStoreGetsItsPreviewWhenAsked) {
  ScratchDir dir;
  options_.store_dir = dir.File("jobs");
  StartServer();
  const CallResult done = Reconstruct(DracoCloud("torus", 20000), {});
  ASSERT_EQ(done.FinalState(), v1::SUCCEEDED) << done.status.error_message();
  server_->Shutdown(absl::ZeroDuration());
  server_.reset();
  StartServer();
  const std::string job = "/api/jobs/" + done.JobId();
  EXPECT_TRUE(absl::StrContains(Get(job).body, "\"has_preview\":true")) << Get(job).body;
  const HttpReply preview = Get(job + "/preview.png");
  ASSERT_EQ(preview.status, 200) << preview.body;
  ExpectPreview(preview.body);
  // The restored job kept no points: the page says so rather than drawing none.
  EXPECT_EQ(Get(job + "/points").status, 409);
}

// A download in the other format is converted within the jobs' memory budget: one whose
// conversion is over the whole budget is refused with 429 and the numbers, not an OOM, and the
// format the job produced is sent as it is. (The job ran without a budget, on a first start of
// the same store.)
TEST_F(HttpApiTest, AConversionOverTheMemoryBudgetIsRefused) {
  ScratchDir dir;
  options_.store_dir = dir.File("jobs");
  StartServer();
  const CallResult done = Reconstruct(DracoCloud("sphere", 2000), {});
  ASSERT_EQ(done.FinalState(), v1::SUCCEEDED) << done.status.error_message();
  server_->Shutdown(absl::ZeroDuration());
  server_.reset();
  options_.memory_budget_bytes = 1000;
  StartServer();
  const std::string job = "/api/jobs/" + done.JobId();
  const HttpReply ply = Get(job + "/mesh.ply");
  EXPECT_EQ(ply.status, 429) << ply.body;
  EXPECT_TRUE(absl::StrContains(ply.body, "RESOURCE_EXHAUSTED")) << ply.body;
  EXPECT_TRUE(absl::StrContains(ply.body, "converting job '" + done.JobId() + "''s mesh to PLY"))
      << ply.body;
  EXPECT_TRUE(absl::StrContains(ply.body, "over the server's memory budget of 1000 bytes"))
      << ply.body;
  const HttpReply drc = Get(job + "/mesh.drc");
  ASSERT_EQ(drc.status, 200) << drc.body;
  EXPECT_EQ(drc.body, done.Mesh());
}

TEST_F(HttpApiTest, AStoppingServerAnswersWaitingEventsRequestsAtOnce) {
  // With a store, a job still running at the stop is kept unfinished: it never ends here, so
  // only the stop can end a request waiting for its events.
  ScratchDir dir;
  options_.store_dir = dir.File("jobs");
  HoldDecodes();
  StartServer();
  const std::string id = StartHeldJob();
  const std::string events = "/api/jobs/" + id + "/events?after=1000000&wait=20";
  HttpReply waited;
  absl::Duration took;
  std::thread request([&] {
    const absl::Time start = absl::Now();
    waited = Get(events);
    took = absl::Now() - start;
  });
  // Whether the request is waiting when the stop comes or arrives after it, it is answered at
  // once (Shutdown's contract covers both): no order needs waiting for.
  server_->Shutdown(absl::ZeroDuration());
  request.join();
  EXPECT_EQ(waited.status, 200) << waited.body;
  EXPECT_TRUE(absl::StrContains(waited.body, "\"done\":false")) << waited.body;
  EXPECT_LT(took, absl::Seconds(10)) << "the stop did not end the wait";
}

TEST_F(HttpApiTest, CancelStopsARunningJobAndItHasNoMesh) {
  HoldDecodes();
  StartServer();
  const std::string id = StartHeldJob();
  const std::string job = "/api/jobs/" + id;
  EXPECT_EQ(Get(job + "/mesh.drc").status, 409);
  EXPECT_EQ(Get(job + "/preview.png").status, 409);
  const HttpReply cancel = Post(job + "/cancel");
  ASSERT_EQ(cancel.status, 200) << cancel.body;
  ASSERT_TRUE(WaitFor([&] { return absl::StrContains(Get(job).body, "\"CANCELLED\""); }, 30));
  EXPECT_TRUE(absl::StrContains(Get(job).body, "cancelled by the client")) << Get(job).body;
  EXPECT_EQ(Get(job + "/mesh.ply").status, 409);
}

}  // namespace
}  // namespace membrane::testing

// `membrane synth` then `membrane reconstruct --local` then `membrane check --json`: the whole
// pipeline gives a closed mesh with the shape's topology.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/support/cli_runner.h"
#include "core/io/mesh_io.h"
#include "tests/cli/json_value.h"
#include "tests/support/survey_cloud.h"
#include "tests/support/scratch_dir.h"

namespace membrane::testing {
namespace {

using ::testing::HasSubstr;

class ReconstructTest : public ::testing::Test {
 protected:
  CliResult Run(const std::vector<std::string>& args) { return RunMembrane(args, dir_.path()); }

  // Synthesizes `shape`, reconstructs it into `mesh_name` and returns `check --json` of it.
  JsonValue ReconstructAndCheck(const std::string& shape, int points,
                                const std::string& mesh_name) {
    const std::string cloud = dir_.File(shape + ".ply");
    const CliResult synth = Run({"synth", shape, "-o", cloud, "--points", std::to_string(points)});
    EXPECT_EQ(synth.exit_code, 0) << synth.err;
    const std::string mesh = dir_.File(mesh_name);
    const CliResult reconstruct = Run({"reconstruct", cloud, "-o", mesh, "--local"});
    EXPECT_EQ(reconstruct.exit_code, 0) << reconstruct.err;
    EXPECT_TRUE(std::filesystem::exists(mesh));
    // The paper's table and the summary line go to stdout.
    EXPECT_THAT(reconstruct.out, HasSubstr("plate size | soft voxels | started contractions"));
    EXPECT_THAT(reconstruct.out, HasSubstr("hard voxels"));
    // Not a terminal: progress comes as plain lines, one per generation, never rewritten.
    EXPECT_THAT(reconstruct.err, HasSubstr(", plate size 1: "));
    EXPECT_EQ(reconstruct.err.find('\r'), std::string::npos);
    const CliResult check = Run({"check", mesh, "--json"});
    EXPECT_EQ(check.exit_code, 0) << check.err;
    std::optional<JsonValue> report = ParseJson(check.out);
    EXPECT_TRUE(report.has_value()) << check.out;
    return report.value_or(JsonValue{});
  }

  static std::vector<int> Genus(const JsonValue& report) {
    std::vector<int> genus;
    if (const JsonValue* g = report.Find("genus")) {
      for (const JsonValue& v : g->array) genus.push_back(static_cast<int>(v.number));
    }
    return genus;
  }

  static bool Flag(const JsonValue& report, const std::string& key) {
    const JsonValue* v = report.Find(key);
    return v != nullptr && v->type == JsonValue::Type::kBool && v->boolean;
  }

  ScratchDir dir_;
};

TEST_F(ReconstructTest, SphereGivesOneClosedGenusZeroShell) {
  const JsonValue report = ReconstructAndCheck("sphere", 20000, "sphere_mesh.ply");
  EXPECT_TRUE(Flag(report, "closed"));
  EXPECT_TRUE(Flag(report, "manifold"));
  EXPECT_TRUE(Flag(report, "oriented"));
  ASSERT_NE(report.Find("shells"), nullptr);
  EXPECT_EQ(report.Find("shells")->number, 1);
  EXPECT_EQ(Genus(report), std::vector<int>{0});
}

// Long stages show how far they are and for how long they have run (here from their start,
// whatever their length: the hidden --progress-after 0). Not a terminal: plain lines.
TEST_F(ReconstructTest, StageLinesShowAFractionAndTheElapsedTime) {
  const std::string cloud = dir_.File("torus.ply");
  ASSERT_EQ(Run({"synth", "torus", "-o", cloud, "--points", "20000"}).exit_code, 0);
  const CliResult r =
      Run({"reconstruct", cloud, "-o", dir_.File("m.ply"), "--local", "--progress-after", "0"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, ::testing::ContainsRegex("\nsurface: [0-9]+% in [0-9.]+ s\n"));
  EXPECT_THAT(r.err, HasSubstr("\nsurface: 100% in "));
  EXPECT_THAT(r.err, HasSubstr("\ncheck: 100% in "));
  // A stage that does not count its work shows its time alone.
  EXPECT_THAT(r.err, ::testing::ContainsRegex("\nencode: [0-9.]+ s\n"));
  // -q shows none of it.
  const CliResult quiet = Run({"reconstruct", cloud, "-o", dir_.File("m.ply"), "--local",
                               "--progress-after", "0", "-q"});
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_EQ(quiet.err.find("% in "), std::string::npos) << quiet.err;
}

TEST_F(ReconstructTest, QuietLeavesOnlyTheSummaryLineOnStdout) {
  const std::string cloud = dir_.File("sphere.ply");
  ASSERT_EQ(Run({"synth", "sphere", "-o", cloud, "--points", "5000"}).exit_code, 0);
  const CliResult r = Run({"reconstruct", cloud, "-o", dir_.File("m.ply"), "--local", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("plate size |"), std::string::npos) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  EXPECT_THAT(r.out, HasSubstr("hard voxels"));
  EXPECT_EQ(r.err, "");
}

// Radial noise of 0.05 on a unit sphere (2 formula-(1) voxels): by default the voxel follows
// the noise (13 times formula (1)'s), and the sphere comes back a sphere, with one warning
// saying so. At formula (1)'s size, given, the points scatter over several voxels: the run
// succeeds but says, after its summary and even with --quiet, that the membrane may have false
// handles and which voxel size suits such points; the statistics hold the same sentence. With
// that size the sphere is a sphere again, and nothing is said.
TEST_F(ReconstructTest, ScatteredPointsAreWarnedAboutWithAVoxelSizeThatSuitsThem) {
  const std::string cloud = dir_.File("noisy.ply");
  ASSERT_EQ(Run({"synth", "sphere", "-o", cloud, "--points", "50000", "--noise", "0.05", "--seed",
                 "3"})
                .exit_code,
            0);
  const std::string defaults = dir_.File("default.json");
  const CliResult d = Run({"reconstruct", cloud, "-o", dir_.File("default_mesh.ply"), "--local",
                           "--quiet", "--surface", "cuberille", "--stats-json", defaults});
  ASSERT_EQ(d.exit_code, 0) << d.err;
  EXPECT_THAT(d.err, ::testing::StartsWith("warning: the points scatter across their surface"));
  EXPECT_EQ(std::count(d.err.begin(), d.err.end(), '\n'), 1) << d.err;
  EXPECT_THAT(d.out, HasSubstr("1 shell, genus [0]"));
  const std::optional<JsonValue> chosen = ParseJson(ReadWholeFile(defaults));
  ASSERT_TRUE(chosen.has_value());
  const double formula = chosen->Find("formula_voxel_size")->number;
  EXPECT_GT(chosen->Find("voxel_size")->number, 4 * formula);
  EXPECT_GT(chosen->Find("point_noise")->number, formula);

  const std::string stats = dir_.File("noisy.json");
  const CliResult r = Run({"reconstruct", cloud, "-o", dir_.File("noisy_mesh.ply"), "--local",
                           "--quiet", "--surface", "cuberille", "--stats-json", stats,
                           "--voxel-size", absl::StrCat(formula)});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, ::testing::StartsWith("warning: the points scatter"));
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  const std::optional<JsonValue> json = ParseJson(ReadWholeFile(stats));
  ASSERT_TRUE(json.has_value());
  ASSERT_EQ(json->Find("warnings")->array.size(), 1u);
  const std::string& warning = json->Find("warnings")->array[0].string;
  EXPECT_THAT(r.err, HasSubstr(warning));
  const size_t at = warning.find("a voxel size of ");
  ASSERT_NE(at, std::string::npos) << warning;
  const std::string size = warning.substr(at + 16, warning.find(' ', at + 16) - (at + 16));
  const CliResult mended = Run({"reconstruct", cloud, "-o", dir_.File("mended.ply"), "--local",
                                "--quiet", "--surface", "cuberille", "--voxel-size", size});
  ASSERT_EQ(mended.exit_code, 0) << mended.err;
  EXPECT_EQ(mended.err, "");
  EXPECT_THAT(mended.out, HasSubstr("1 shell, genus [0]"));
}

// A scan in UTM coordinates: read in double and moved near 0, reconstructed there, and written
// back at its coordinates. Read as float32 (0.25 m apart at the northing), it would be
// refused.
TEST_F(ReconstructTest, GeoreferencedCloudComesBackAtItsCoordinates) {
  const std::string sphere = dir_.File("sphere.ply");
  ASSERT_EQ(Run({"synth", "sphere", "-o", sphere, "--points", "5000"}).exit_code, 0);
  const std::string cloud = dir_.File("survey.xyz");
  WriteSurveyCopy(sphere, cloud);
  const std::string mesh = dir_.File("survey_mesh.ply");
  const std::string stats = dir_.File("survey.json");
  const CliResult r = Run({"reconstruct", cloud, "-o", mesh, "--local", "--stats-json", stats});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err,
              ::testing::ContainsRegex("moved by -51234[5-7], -412345[6-8], 0 for float32"));
  // The origin is the first point in whole units: within the unit sphere of the offset.
  std::optional<JsonValue> json = ParseJson(ReadWholeFile(stats));
  ASSERT_TRUE(json.has_value());
  const JsonValue* origin = json->Find("origin");
  ASSERT_NE(origin, nullptr);
  ASSERT_EQ(origin->array.size(), 3u);
  EXPECT_NEAR(origin->array[0].number, kSurveyOffset[0], 1.5);
  EXPECT_NEAR(origin->array[1].number, kSurveyOffset[1], 1.5);
  EXPECT_EQ(origin->array[2].number, 0);  // a height of 102.5 is left where it is
  absl::StatusOr<TriangleMesh> read = ReadMesh(mesh);
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_NE(read->origin, (Origin3d{0, 0, 0}));
  // The unit sphere's mesh is centred where the scan is, to a fraction of a voxel (0.04 here).
  const std::array<double, 3> centre = FileBoxCentre(*read);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(centre[k], kSurveyOffset[k], 0.02) << k;
  const CliResult check = Run({"check", mesh, "--json"});
  EXPECT_EQ(check.exit_code, 0) << check.err;
  std::optional<JsonValue> report = ParseJson(check.out);
  ASSERT_TRUE(report.has_value()) << check.out;
  EXPECT_TRUE(Flag(*report, "closed"));
  EXPECT_EQ(Genus(*report), std::vector<int>{0});
  ASSERT_NE(report->Find("self_intersections"), nullptr);
  EXPECT_EQ(report->Find("self_intersections")->number, 0);
}

// .stl and .drc hold float32 only: the input's coordinates cannot be kept there, and the
// command says so before any work.
TEST_F(ReconstructTest, GeoreferencedCloudToFloatOnlyFormatsIsRefusedBeforeWork) {
  const std::string sphere = dir_.File("sphere.ply");
  ASSERT_EQ(Run({"synth", "sphere", "-o", sphere, "--points", "2000"}).exit_code, 0);
  const std::string cloud = dir_.File("survey.xyz");
  WriteSurveyCopy(sphere, cloud);
  for (const char* name : {"survey.stl", "survey.drc"}) {
    const std::string mesh = dir_.File(name);
    const CliResult r = Run({"reconstruct", cloud, "-o", mesh, "--local"});
    EXPECT_EQ(r.exit_code, 3) << name;
    EXPECT_THAT(ErrorLines(r.err), ::testing::ElementsAre(HasSubstr("write .ply or .obj")));
    EXPECT_THAT(r.err, ::testing::Not(HasSubstr("shrink:")));
    EXPECT_FALSE(std::filesystem::exists(mesh)) << name;
  }
}

TEST_F(ReconstructTest, TorusGivesGenusOne) {
  const JsonValue report = ReconstructAndCheck("torus", 20000, "torus_mesh.obj");
  EXPECT_TRUE(Flag(report, "closed"));
  EXPECT_TRUE(Flag(report, "manifold"));
  EXPECT_EQ(Genus(report), std::vector<int>{1});
}

TEST_F(ReconstructTest, CuberilleSurfaceToDracoIsClosed) {
  const std::string cloud = dir_.File("sphere.xyz");
  ASSERT_EQ(Run({"synth", "sphere", "-o", cloud, "--points", "5000"}).exit_code, 0);
  const std::string mesh = dir_.File("sphere.drc");
  const CliResult r = Run({"reconstruct", cloud, "-o", mesh, "--local", "--surface", "cuberille",
                           "--no-relax", "--schedule", "linear", "--quantization", "16"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CliResult check = Run({"check", mesh});
  EXPECT_EQ(check.exit_code, 0) << check.err;
  EXPECT_THAT(check.out, HasSubstr("closed: yes"));
}

// The .drc file holds positions on an 11-bit grid, and the surface is built and checked on
// that grid. Checked in float32 and quantized afterwards, this cloud's file would hold 57
// crossing face pairs while the statistics said 0.
TEST_F(ReconstructTest, DracoFileChecksAsTheStatisticsSay) {
  const std::string cloud = dir_.File("cube.ply");
  ASSERT_EQ(Run({"synth", "cube-pinholes", "-o", cloud, "--points", "20000"}).exit_code, 0);
  const std::string mesh = dir_.File("cube.drc"), stats = dir_.File("cube.json");
  const CliResult r = Run({"reconstruct", cloud, "-o", mesh, "--local", "--stats-json", stats});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("on the output's 11-bit grid"));
  const CliResult check = Run({"check", mesh, "--json"});
  ASSERT_EQ(check.exit_code, 0) << check.err;
  const std::optional<JsonValue> file = ParseJson(check.out);
  ASSERT_TRUE(file.has_value()) << check.out;
  EXPECT_TRUE(Flag(*file, "closed"));
  EXPECT_TRUE(Flag(*file, "manifold"));
  ASSERT_NE(file->Find("self_intersections"), nullptr);
  EXPECT_EQ(file->Find("self_intersections")->number, 0);
  EXPECT_EQ(file->Find("degenerate_faces")->number, 0);
  const std::optional<JsonValue> json = ParseJson(ReadWholeFile(stats));
  ASSERT_TRUE(json.has_value());
  const JsonValue* q = json->Find("quantization");
  ASSERT_NE(q, nullptr);
  EXPECT_EQ(q->Find("requested_bits")->number, 11);
  EXPECT_EQ(q->Find("bits")->number, 11);
  EXPECT_GT(q->Find("step")->number, 0);
  ASSERT_NE(q->Find("max_position_error"), nullptr);
  EXPECT_NEAR(q->Find("max_position_error")->number, q->Find("step")->number / 2, 1e-9);
  EXPECT_THAT(r.err, HasSubstr("each coordinate within"));
  EXPECT_EQ(json->Find("mesh")->Find("self_intersections")->number, 0);
}

// A grid too coarse for any surface (3 bits: 7 steps across the box): the file is written
// lossless rather than crossed, and the statistics say so.
TEST_F(ReconstructTest, TooCoarseAGridGivesALosslessFileAndSaysSo) {
  const std::string cloud = dir_.File("sphere.ply");
  ASSERT_EQ(Run({"synth", "sphere", "-o", cloud, "--points", "5000"}).exit_code, 0);
  const std::string mesh = dir_.File("sphere.drc"), stats = dir_.File("sphere.json");
  const CliResult r = Run({"reconstruct", cloud, "-o", mesh, "--local", "--quantization", "3",
                           "--stats-json", stats});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("in float32 (on the 3-bit grid asked for, faces crossed)"));
  const std::optional<JsonValue> json = ParseJson(ReadWholeFile(stats));
  ASSERT_TRUE(json.has_value());
  EXPECT_EQ(json->Find("quantization")->Find("requested_bits")->number, 3);
  EXPECT_EQ(json->Find("quantization")->Find("bits")->number, 0);
  const CliResult check = Run({"check", mesh, "--json"});
  const std::optional<JsonValue> file = ParseJson(check.out);
  ASSERT_TRUE(file.has_value()) << check.out;
  EXPECT_EQ(file->Find("self_intersections")->number, 0);
  EXPECT_EQ(file->Find("degenerate_faces")->number, 0);
  EXPECT_TRUE(Flag(*file, "closed"));
}

TEST_F(ReconstructTest, ThreadsGiveTheSameFile) {
  // The fit's slabs and the check's cells are shared among the threads: the output file must
  // not depend on how many there are.
  const std::string cloud = dir_.File("torus.ply");
  ASSERT_EQ(Run({"synth", "torus", "-o", cloud, "--points", "20000"}).exit_code, 0);
  std::vector<std::string> files;
  for (const char* threads : {"1", "3"}) {
    const std::string mesh = dir_.File(std::string("torus-") + threads + ".drc");
    const CliResult r = Run({"reconstruct", cloud, "-o", mesh, "--local", "--threads", threads});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    files.push_back(ReadWholeFile(mesh));
  }
  ASSERT_FALSE(files[0].empty());
  EXPECT_TRUE(files[0] == files[1]) << "the .drc files differ";
}

TEST_F(ReconstructTest, ThreadsOutOfRangeOrWithoutLocalAreRefused) {
  const std::string cloud = dir_.File("sphere.ply");
  ASSERT_EQ(Run({"synth", "sphere", "-o", cloud, "--points", "2000"}).exit_code, 0);
  const std::string mesh = dir_.File("sphere.ply.out.ply");
  const CliResult many = Run({"reconstruct", cloud, "-o", mesh, "--local", "--threads", "300"});
  EXPECT_EQ(many.exit_code, 3);
  EXPECT_THAT(many.err, HasSubstr("--threads"));
  const CliResult remote = Run({"reconstruct", cloud, "-o", mesh, "--threads", "2"});
  EXPECT_EQ(remote.exit_code, 2);
  EXPECT_THAT(remote.err, HasSubstr("--local"));
}

// --target-faces: a .drc file of at most that many faces that checks closed, manifold and
// uncrossed with the torus's genus; the summary line and the statistics give the faces before
// and after and the error added.
TEST_F(ReconstructTest, TargetFacesGivesADecimatedTorus) {
  const std::string cloud = dir_.File("torus.ply");
  ASSERT_EQ(Run({"synth", "torus", "-o", cloud, "--points", "20000"}).exit_code, 0);
  const std::string mesh = dir_.File("torus.drc"), stats = dir_.File("torus.json");
  const CliResult r = Run({"reconstruct", cloud, "-o", mesh, "--local", "--target-faces", "2000",
                           "--stats-json", stats});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("; decimated "));
  EXPECT_THAT(r.out, HasSubstr(" faces (target 2000), moved by at most "));
  EXPECT_THAT(r.err, HasSubstr("decimate: "));
  const CliResult check = Run({"check", mesh, "--json"});
  ASSERT_EQ(check.exit_code, 0) << check.err;
  const std::optional<JsonValue> file = ParseJson(check.out);
  ASSERT_TRUE(file.has_value()) << check.out;
  EXPECT_TRUE(Flag(*file, "closed"));
  EXPECT_TRUE(Flag(*file, "manifold"));
  EXPECT_EQ(file->Find("self_intersections")->number, 0);
  EXPECT_EQ(file->Find("degenerate_faces")->number, 0);
  EXPECT_LE(file->Find("faces")->number, 2000);
  EXPECT_EQ(Genus(*file), std::vector<int>{1});
  const std::optional<JsonValue> json = ParseJson(ReadWholeFile(stats));
  ASSERT_TRUE(json.has_value());
  const JsonValue* d = json->Find("decimation");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->Find("target_faces")->number, 2000);
  EXPECT_GT(d->Find("faces_before")->number, 10000);
  EXPECT_EQ(d->Find("faces_after")->number, file->Find("faces")->number);
  EXPECT_GT(d->Find("max_error")->number, 0);
  EXPECT_GE(d->Find("max_error")->number, d->Find("mean_error")->number);
  EXPECT_GT(json->Find("seconds")->Find("decimate")->number, 0);
}

TEST_F(ReconstructTest, TargetFacesBelowFourIsRefusedBeforeWork) {
  const std::string cloud = dir_.File("sphere.ply");
  ASSERT_EQ(Run({"synth", "sphere", "-o", cloud, "--points", "2000"}).exit_code, 0);
  const CliResult r =
      Run({"reconstruct", cloud, "-o", dir_.File("m.ply"), "--local", "--target-faces", "3"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(r.err, HasSubstr("--target-faces 3"));
  EXPECT_THAT(r.err, ::testing::Not(HasSubstr("voxelize")));
}

}  // namespace
}  // namespace membrane::testing

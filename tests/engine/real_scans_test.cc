// The models of ../shared/data: the expected shells and genus listed in its README (the second
// batch's cloud JSONs hold the same), at 1x, 1.25x, 1.5x and 2x the formula-(1) voxel size.
// Skips when ../shared/data is absent. A run that misses prints where its handles and merges
// are (voxel coordinates of the loops and contacts).
#include <array>
#include <iostream>
#include <string>
#include <tuple>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_replace.h"
#include "core/engine/piece_separation.h"
#include "core/engine/voxel_topology.h"
#include "gtest/gtest.h"
#include "tests/support/shared_data.h"
#include "tests/support/shared_models.h"
#include "tests/support/shrink_fixture.h"
#include "tests/support/topology_locator.h"

namespace membrane {
namespace {

using testing::SharedModel;

struct ScanRun {
  const SharedModel* model;
  std::string kind;
  double factor;
  std::string Cloud() const { return absl::StrCat(model->model, "-", kind); }
};

void PrintTo(const ScanRun& r, std::ostream* os) { *os << r.Cloud() << " at " << r.factor << "x"; }

// The runs the shrink gets wrong (issue 18): each still runs and prints what it gives and
// where the handles and merges are, and is reported as skipped. A run in this list that comes
// out right fails, so that the list is kept to what is still wrong.
// `reason` says what the miss is made of, measured with bench_topology --data-genus, --probe
// and --reference (tests/bench/2026-12-03-topology-data-genus.txt).
struct KnownMiss {
  const char* cloud;
  double factor;
  const char* reason;
};
// Empty: every run of ../shared/data is right.
constexpr std::array<KnownMiss, 0> kKnownMisses{};

// The known miss of `run`, or nullptr.
const KnownMiss* FindKnownMiss(const ScanRun& run) {
  for (const KnownMiss& k : kKnownMisses)
    if (run.Cloud() == k.cloud && run.factor == k.factor) return &k;
  return nullptr;
}

std::vector<ScanRun> AllRuns() {
  std::vector<ScanRun> runs;
  for (const SharedModel& m : testing::SharedModels()) {
    for (const std::string& kind : m.kinds) {
      for (double factor : {1.0, 1.25, 1.5, 2.0}) runs.push_back({&m, kind, factor});
    }
  }
  return runs;
}

std::string Expected(const SharedModel& m) {
  return absl::StrCat("shells=", m.expected.shells, " genus=[",
                      m.genus_asserted ? absl::StrJoin(m.expected.genus, ",") : "any", "]");
}

// The cloud `name` of ../shared/data shrunk at `factor` x its formula-(1) voxel size.
absl::StatusOr<testing::ShrinkRun> ShrinkSharedCloud(const std::string& data_dir,
                                                     const std::string& name, double factor) {
  absl::StatusOr<PointCloud> cloud = testing::ReadSharedCloud(data_dir, name);
  if (!cloud.ok()) return cloud.status();
  return testing::ShrinkCloud(*cloud, factor);
}

class RealScanTest : public ::testing::TestWithParam<ScanRun> {};

TEST_P(RealScanTest, HasTheExpectedShellsAndGenus) {
  MEMBRANE_REQUIRE_SHARED_DATA(data_dir);
  const ScanRun& r = GetParam();
  auto run = ShrinkSharedCloud(data_dir, r.Cloud(), r.factor);
  ASSERT_TRUE(run.ok()) << run.status();
  RecordProperty("topology", run->Describe());
  const std::string what = absl::StrFormat("%s at %gx: %s", r.Cloud(), r.factor, run->Describe());
  std::cout << what << "\n";
  ASSERT_TRUE(run->invariants.ok()) << what;
  EXPECT_EQ(run->topology.cavities, 0) << what;
  const bool right =
      testing::HasExpectedTopology(*r.model, run->topology.shells, run->topology.genus);
  const std::string where =
      right ? "" : testing::LocateHandlesAndContacts(run->voxels.grid);
  if (const KnownMiss* miss = FindKnownMiss(r); miss != nullptr) {
    EXPECT_FALSE(right) << what << ": a known miss came out right; remove it from kKnownMisses";
    if (!right) {
      GTEST_SKIP() << "known miss (issue 18): " << what << ", expected " << Expected(*r.model)
                   << " (" << miss->reason << ")\n" << where;
    }
    return;
  }
  EXPECT_TRUE(right) << what << ", expected " << Expected(*r.model) << "\n" << where;
}

// The three objects of cow-spot-belt at 1.5x: the cut between the pieces opens loops through
// itself; returning the cut voxels that close them, and cutting the webs far from the data
// too, separates the three shells with fewer handles than the joined shell had (the handle
// retry, run from the plates of 4, has closed one web across missing data before). Spot's
// two handles go around a hollow carved behind its scanned walls; the gap refill's pockets
// close them (the run is asserted above).
TEST(RealScanSeparation, CowSpotBeltAt1p5xComesApartWithoutNewHandles) {
  MEMBRANE_REQUIRE_SHARED_DATA(data_dir);
  auto run = ShrinkSharedCloud(data_dir, "cow-spot-belt-scan", 1.5);
  ASSERT_TRUE(run.ok()) << run.status();
  const PieceSeparationStats& sep = run->result.separation;
  const std::string what = absl::StrFormat(
      "%s; pieces %d, %d/%d -> %d/%d, loops closed %d", run->Describe(), sep.pieces,
      sep.shells_before, sep.genus_before, sep.shells_after, sep.genus_after, sep.loops_closed);
  ASSERT_TRUE(run->invariants.ok()) << what;
  EXPECT_EQ(sep.pieces, 3) << what;
  EXPECT_TRUE(sep.separated) << what;
  EXPECT_GT(sep.loops_closed, 0) << what;
  EXPECT_EQ(run->topology.shells, 3) << what;
  EXPECT_EQ(run->topology.cavities, 0) << what;
  EXPECT_LT(TotalGenus(run->topology), sep.genus_before) << what;
  EXPECT_TRUE(run->result.handle_retry.kept) << what;
  EXPECT_GT(run->result.refill.loops_closed, 0) << what;
}

// Spot's scan at 0.85x the formula-(1) voxel: finer than the cloud's spacing, as the
// formula's voxel is for a noise-free scan of millions of points, so the parts under the
// belly the scanner sees at grazing angles leave gaps a few voxels wide. The plates of 4
// notch the webs the membrane spans there (short-loop tunnels and wall notches) into two
// handles that no later plate cuts; the handle retry runs the generations again from the
// plates of 4 without those tunnels and keeps its result, whose webs hang on 14% hard
// voxels (tests/bench/2026-12-05-dense-genus.txt).
TEST(RealScanDense, SpotScanAtAFinerVoxelKeepsNoWebHandle) {
  MEMBRANE_REQUIRE_SHARED_DATA(data_dir);
  auto run = ShrinkSharedCloud(data_dir, "spot-scan", 0.85);
  ASSERT_TRUE(run.ok()) << run.status();
  EXPECT_EQ(run->topology.shells, 1) << run->Describe();
  const std::string miss = testing::RetryMissOfWebs(*run, 4);
  EXPECT_TRUE(miss.empty()) << miss << "\n" << testing::LocateHandlesAndContacts(run->voxels.grid);
}

INSTANTIATE_TEST_SUITE_P(SharedData, RealScanTest, ::testing::ValuesIn(AllRuns()),
                         [](const auto& info) {
                           const ScanRun& r = info.param;
                           return absl::StrReplaceAll(absl::StrCat(r.Cloud(), "_x", r.factor),
                                                      {{"-", "_"}, {".", "p"}});
                         });

}  // namespace
}  // namespace membrane

#include "core/pipeline/stage_lines.h"

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

using ::testing::EndsWith;
using ::testing::HasSubstr;
using ::testing::Not;

// The shrink's line names each pass after the generations that changed the membrane, so that
// a topology unlike the generations' one is explained on the line itself.
TEST(StageLines, ShrinkLineNamesThePassesAfterTheGenerationsThatChangedSomething) {
  ReconstructionReport report;
  report.generations.resize(8);
  report.piece_separation.pieces = 3;
  report.piece_separation.separated = true;
  report.piece_separation.shells_after = 3;
  report.piece_separation.cut_voxels = 942;
  report.piece_separation.hard_cut_voxels = 2;
  report.hole_opening.opened = 1;
  report.gap_refill.refilled_voxels = 4702;
  const std::string line = StageFinishedLine(PipelineStage::kShrink, report);
  EXPECT_THAT(line, HasSubstr("3 pieces of data separated into 3 shells (942 voxels cut, 2 of "
                              "them hard)"));
  EXPECT_THAT(line, HasSubstr("; 1 plugged hole opened;"));
  EXPECT_THAT(line, EndsWith("; 4702 voxels refilled in data gaps"));
}

// The interior a coarser membrane held is named first: it decided what the generations saw.
TEST(StageLines, ShrinkLineNamesTheInteriorHeldByACoarserMembrane) {
  ReconstructionReport report;
  report.generations.resize(9);
  report.interior_guard.frozen_voxels = 16346613;
  report.gap_refill.refilled_voxels = 66093;
  const std::string line = StageFinishedLine(PipelineStage::kShrink, report);
  EXPECT_THAT(line, HasSubstr("; 16346613 voxels of the interior held by a coarser membrane; "
                              "66093 voxels refilled in data gaps"));
  report.interior_guard.frozen_voxels = 0;
  EXPECT_THAT(StageFinishedLine(PipelineStage::kShrink, report), Not(HasSubstr("interior")));
}

TEST(StageLines, ShrinkLineSaysWhenPiecesOfDataStayJoined) {
  ReconstructionReport report;
  report.piece_separation.pieces = 2;
  report.piece_separation.shells_after = 2;  // a cut was tried, and refused
  report.hole_opening.opened = 2;
  const std::string line = StageFinishedLine(PipelineStage::kShrink, report);
  EXPECT_THAT(line, HasSubstr("; 2 pieces of data left joined (their cut refused)"));
  EXPECT_THAT(line, Not(HasSubstr("hard)")));
  EXPECT_THAT(line, EndsWith("; 2 plugged holes opened"));
}

TEST(StageLines, ShrinkLineIsQuietAboutPassesThatChangedNothing) {
  ReconstructionReport report;
  report.piece_separation.pieces = 1;
  const std::string line = StageFinishedLine(PipelineStage::kShrink, report);
  EXPECT_THAT(line, EndsWith("connected to the membrane"));
  EXPECT_THAT(line, Not(HasSubstr("pieces")));
}

}  // namespace
}  // namespace membrane

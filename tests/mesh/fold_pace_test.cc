// The pace of the caps' folds (core/mesh/fold_pace.h): a region stalls once its pairs fall by
// less than the share asked over the window, and not before it has that many rounds.
#include "core/mesh/fold_pace.h"

#include <vector>

#include "gtest/gtest.h"

namespace membrane {
namespace {

// Records `rounds` (each one count per region) and returns whether each region has stalled
// after the last.
std::vector<bool> StalledAfter(const std::vector<std::vector<int64_t>>& rounds, int window,
                               double fall) {
  FoldPace pace(static_cast<int>(rounds[0].size()), window, fall);
  for (const auto& pairs : rounds) pace.Record(pairs);
  std::vector<bool> stalled;
  for (size_t r = 0; r < rounds[0].size(); ++r)
    stalled.push_back(pace.Stalled(static_cast<int>(r)));
  return stalled;
}

TEST(FoldPace, AFoldWhosePairsHoldStalls) {
  // Region 0 falls 194 -> 74 over 4 rounds (an untangled cap's); region 1 holds at 20 -> 23;
  // region 2 falls 100 -> 81, less than a fifth; region 3 falls by exactly a fifth.
  const std::vector<std::vector<int64_t>> rounds = {
      {194, 20, 100, 100}, {121, 22, 95, 90}, {76, 23, 90, 85}, {85, 23, 85, 82}, {74, 23, 81, 80}};
  EXPECT_EQ(StalledAfter(rounds, 4, 0.2), (std::vector<bool>{false, true, true, false}));
  // A window longer than the rounds so far: none yet.
  EXPECT_EQ(StalledAfter(rounds, 5, 0.2), (std::vector<bool>{false, false, false, false}));
  // No window: none ever.
  EXPECT_EQ(StalledAfter(rounds, 0, 0.2), (std::vector<bool>{false, false, false, false}));
}

TEST(FoldPace, RoundsCountFromTheFirstWithPairs) {
  // Region 0 has no pairs for two rounds, then holds at 10 for 4 rounds: its window starts
  // at its first pairs. Region 1 clears: no pairs now, so no stall.
  std::vector<std::vector<int64_t>> rounds = {{0, 8}, {0, 8}, {10, 8}, {10, 8}, {10, 8}, {10, 8}};
  EXPECT_EQ(StalledAfter(rounds, 4, 0.2), (std::vector<bool>{false, true}));
  rounds.push_back({10, 0});
  EXPECT_EQ(StalledAfter(rounds, 4, 0.2), (std::vector<bool>{true, false}));
  // A fold that comes back after clearing: more pairs than the 0 of `window` rounds before.
  rounds = {{5, 0}, {0, 0}, {0, 0}, {0, 0}, {3, 0}};
  EXPECT_EQ(StalledAfter(rounds, 3, 0.2), (std::vector<bool>{true, false}));
}

}  // namespace
}  // namespace membrane

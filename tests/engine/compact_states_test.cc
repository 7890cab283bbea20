#include "core/engine/compact_states.h"

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "gtest/gtest.h"

namespace membrane {
namespace {

// States like a shrunk grid's: long runs of outside labels and inside voxels, a stretch of
// noise (every byte differs from the last: stored as bytes), and a partial last chunk.
std::vector<VoxelState> ShrunkLikeStates() {
  std::vector<VoxelState> s;
  const int64_t size = 3 * CompactStates::kChunk + 1234;
  s.reserve(static_cast<size_t>(size));
  std::mt19937 rng(7);
  const VoxelState kinds[] = {OutsideState(3), kInsideSoft, kBoundarySoft, kBoundaryHard,
                              OutsideState(9)};
  while (static_cast<int64_t>(s.size()) < CompactStates::kChunk + 500) {
    const VoxelState v = kinds[rng() % 5];
    const int length = 1 + static_cast<int>(rng() % 3000);
    s.insert(s.end(), static_cast<size_t>(length), v);
  }
  while (static_cast<int64_t>(s.size()) < 2 * CompactStates::kChunk + 100) {
    s.push_back(static_cast<VoxelState>(s.size() % 2 == 0 ? kInsideSoft : OutsideState(5)));
  }
  while (static_cast<int64_t>(s.size()) < size) s.push_back(OutsideState(1));
  s.resize(static_cast<size_t>(size));
  return s;
}

TEST(CompactStates, DecodesToTheStatesEncoded) {
  const std::vector<VoxelState> states = ShrunkLikeStates();
  CompactStates copy;
  ASSERT_TRUE(copy.Encode(states, CancelToken::Never()));
  EXPECT_EQ(copy.size(), static_cast<int64_t>(states.size()));
  std::vector<VoxelState> decoded(states.size(), 0x42);
  ASSERT_TRUE(copy.Decode(absl::MakeSpan(decoded), CancelToken::Never()));
  EXPECT_EQ(decoded, states);
}

// Encoded a range of chunks a task and joined, decoded a range a task: the same runs, bytes
// and states as on one thread (a part of runs, one of bytes, a partial last chunk).
TEST(CompactStates, TheSameCopyOnAnyThreadCount) {
  const std::vector<VoxelState> states = ShrunkLikeStates();
  CompactStates one, three;
  ASSERT_TRUE(one.Encode(states, CancelToken::Never(), 1));
  ASSERT_TRUE(three.Encode(states, CancelToken::Never(), 3));
  EXPECT_EQ(three.encoded_bytes(), one.encoded_bytes());
  EXPECT_EQ(three.size(), one.size());
  for (const CompactStates* copy : {&one, &three}) {
    std::vector<VoxelState> decoded(states.size(), 0x42);
    ASSERT_TRUE(copy->Decode(absl::MakeSpan(decoded), CancelToken::Never(), 3));
    EXPECT_EQ(decoded, states);
  }
  FlatBitset a, b;
  one.OutsidePlane(a);
  three.OutsidePlane(b);
  EXPECT_TRUE(std::equal(a.words(), a.words() + (a.bits() + 63) / 64, b.words()));
}

TEST(CompactStates, RunsTakeLessRoomThanTheBytes) {
  const std::vector<VoxelState> runs(static_cast<size_t>(5 * CompactStates::kChunk),
                                     OutsideState(2));
  CompactStates copy;
  ASSERT_TRUE(copy.Encode(runs, CancelToken::Never()));
  EXPECT_LT(copy.encoded_bytes(), 1000);
  // Noise is kept as bytes, not as runs four times their size.
  std::vector<VoxelState> noise(static_cast<size_t>(CompactStates::kChunk));
  for (size_t i = 0; i < noise.size(); ++i) noise[i] = static_cast<VoxelState>(i % 3);
  ASSERT_TRUE(copy.Encode(noise, CancelToken::Never()));
  EXPECT_LE(copy.encoded_bytes(), CompactStates::kChunk + 64);
  std::vector<VoxelState> decoded(noise.size());
  ASSERT_TRUE(copy.Decode(absl::MakeSpan(decoded), CancelToken::Never()));
  EXPECT_EQ(decoded, noise);
}

TEST(CompactStates, OutsidePlaneMarksTheOutsideVoxels) {
  const std::vector<VoxelState> states = ShrunkLikeStates();
  CompactStates copy;
  ASSERT_TRUE(copy.Encode(states, CancelToken::Never()));
  FlatBitset outside;
  copy.OutsidePlane(outside);
  ASSERT_EQ(outside.bits(), static_cast<int64_t>(states.size()));
  int64_t mismatches = 0;
  for (size_t i = 0; i < states.size(); ++i) {
    mismatches += outside.test(static_cast<int64_t>(i)) != IsOutside(states[i]);
  }
  EXPECT_EQ(mismatches, 0);
}

// A plane of the copy's size (a work plane, whose words an arena holds) keeps its words, and
// whatever its bits were before, they become the copy's outside voxels.
TEST(CompactStates, OutsidePlaneKeepsAPlaneOfItsSize) {
  const std::vector<VoxelState> states = ShrunkLikeStates();
  CompactStates copy;
  ASSERT_TRUE(copy.Encode(states, CancelToken::Never()));
  FlatBitset plane(static_cast<int64_t>(states.size()));
  for (int64_t i = 0; i < plane.bits(); i += 3) plane.set(i);
  const uint64_t* words = plane.words();
  copy.OutsidePlane(plane);
  EXPECT_EQ(plane.words(), words);
  int64_t mismatches = 0;
  for (size_t i = 0; i < states.size(); ++i) {
    mismatches += plane.test(static_cast<int64_t>(i)) != IsOutside(states[i]);
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(CompactStates, ReusedForAShorterCopy) {
  CompactStates copy;
  ASSERT_TRUE(copy.Encode(ShrunkLikeStates(), CancelToken::Never()));
  const std::vector<VoxelState> small = {kInsideSoft, kBoundarySoft, kBoundarySoft, OutsideState(4)};
  ASSERT_TRUE(copy.Encode(small, CancelToken::Never()));
  std::vector<VoxelState> decoded(small.size());
  ASSERT_TRUE(copy.Decode(absl::MakeSpan(decoded), CancelToken::Never()));
  EXPECT_EQ(decoded, small);
}

TEST(CompactStates, CancelledReturnsFalse) {
  const std::vector<VoxelState> states = ShrunkLikeStates();
  CancelToken cancel;
  cancel.Cancel();
  CompactStates copy;
  EXPECT_FALSE(copy.Encode(states, cancel));
  ASSERT_TRUE(copy.Encode(states, CancelToken::Never()));
  std::vector<VoxelState> decoded(states.size());
  EXPECT_FALSE(copy.Decode(absl::MakeSpan(decoded), cancel));
}

}  // namespace
}  // namespace membrane

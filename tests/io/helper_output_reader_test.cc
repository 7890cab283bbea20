// The decode helper's output read as it arrives (core/io/helper_output_reader.h): the records
// land in their vectors whatever pieces the pipe gives them in; a short output, bytes after the
// last section and a count past the limit are each told apart, and the reader never leaves the
// writer blocked.
#include "core/io/helper_output_reader.h"

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "core/geometry/point_cloud.h"

namespace membrane {
namespace {

using Face = std::array<int32_t, 3>;

// A pipe whose read end does not block, closed on destruction.
struct Pipe {
  int read_end = -1;
  int write_end = -1;
  Pipe() {
    int fds[2];
    EXPECT_EQ(pipe2(fds, O_CLOEXEC), 0);
    read_end = fds[0];
    write_end = fds[1];
    fcntl(read_end, F_SETFL, fcntl(read_end, F_GETFL) | O_NONBLOCK);
  }
  void CloseWriteEnd() {
    close(write_end);
    write_end = -1;
  }
  ~Pipe() {
    for (int fd : {read_end, write_end}) {
      if (fd >= 0) close(fd);
    }
  }
};

template <typename T>
void AppendSection(const std::vector<T>& items, std::string& out) {
  const uint64_t count = items.size();
  out.append(reinterpret_cast<const char*>(&count), sizeof count);
  out.append(reinterpret_cast<const char*>(items.data()), items.size() * sizeof(T));
}

std::vector<Point3f> SomePoints(int n) {
  std::vector<Point3f> points;
  for (int i = 0; i < n; ++i) points.push_back({0.5f * i, -1.0f * i, 3.0f + i});
  return points;
}

// Writes `bytes` into `pipe` in pieces of `piece` bytes, draining `reader` after each one,
// then closes the write end and drains to the end. Returns what the last Drain returned.
bool FeedInPieces(const std::string& bytes, size_t piece, Pipe& pipe, HelperOutputReader& reader) {
  for (size_t at = 0; at < bytes.size(); at += piece) {
    const size_t n = std::min(piece, bytes.size() - at);
    EXPECT_EQ(write(pipe.write_end, bytes.data() + at, n), static_cast<ssize_t>(n));
    EXPECT_TRUE(reader.Drain(pipe.read_end));
  }
  pipe.CloseWriteEnd();
  return reader.Drain(pipe.read_end);
}

TEST(HelperOutputReader, FillsEachSectionWhateverPiecesItComesIn) {
  const std::vector<Point3f> points = SomePoints(37);
  const std::vector<Face> faces = {{0, 1, 2}, {2, 1, 3}, {36, 35, 0}};
  std::string bytes;
  AppendSection(points, bytes);
  AppendSection(faces, bytes);
  for (size_t piece : {size_t{1}, size_t{3}, size_t{7}, size_t{12}, size_t{4096}}) {
    Pipe pipe;
    std::vector<Point3f> read_points;
    std::vector<Face> read_faces;
    HelperOutputReader reader(1 << 20);
    reader.Add(&read_points);
    reader.Add(&read_faces);
    EXPECT_FALSE(FeedInPieces(bytes, piece, pipe, reader)) << "end of file is reported";
    EXPECT_EQ(reader.state(), HelperOutputReader::State::kComplete) << piece;
    EXPECT_EQ(read_points, points) << piece;
    EXPECT_EQ(read_faces, faces) << piece;
    EXPECT_EQ(reader.bytes_read(), bytes.size());
    EXPECT_EQ(reader.first_count(), std::optional<uint64_t>(37));
  }
}

TEST(HelperOutputReader, TheFirstCountComesOnlyWithItsEighthByte) {
  Pipe pipe;
  std::vector<Point3f> points;
  HelperOutputReader reader(1 << 20);
  reader.Add(&points);
  const uint64_t count = 5;
  ASSERT_EQ(write(pipe.write_end, &count, 7), 7);
  EXPECT_TRUE(reader.Drain(pipe.read_end));
  EXPECT_FALSE(reader.first_count().has_value());
  EXPECT_EQ(reader.bytes_read(), 7u);
  ASSERT_EQ(write(pipe.write_end, reinterpret_cast<const char*>(&count) + 7, 1), 1);
  EXPECT_TRUE(reader.Drain(pipe.read_end));
  EXPECT_EQ(reader.first_count(), std::optional<uint64_t>(5));
  EXPECT_EQ(reader.state(), HelperOutputReader::State::kReading);
}

TEST(HelperOutputReader, AnEmptySectionIsWholeAtItsCount) {
  std::string bytes;
  AppendSection(std::vector<Point3f>(), bytes);
  AppendSection(std::vector<Face>{{1, 2, 3}}, bytes);
  Pipe pipe;
  std::vector<Point3f> points = SomePoints(2);  // resized to the count
  std::vector<Face> faces;
  HelperOutputReader reader(1 << 20);
  reader.Add(&points);
  reader.Add(&faces);
  FeedInPieces(bytes, 5, pipe, reader);
  EXPECT_EQ(reader.state(), HelperOutputReader::State::kComplete);
  EXPECT_TRUE(points.empty());
  EXPECT_EQ(faces, (std::vector<Face>{{1, 2, 3}}));
}

TEST(HelperOutputReader, AShortOutputIsStillReading) {
  std::string bytes;
  AppendSection(SomePoints(10), bytes);
  bytes.resize(bytes.size() - 1);
  Pipe pipe;
  std::vector<Point3f> points;
  HelperOutputReader reader(1 << 20);
  reader.Add(&points);
  FeedInPieces(bytes, 64, pipe, reader);
  EXPECT_EQ(reader.state(), HelperOutputReader::State::kReading);
}

TEST(HelperOutputReader, BytesAfterTheLastSectionAreTrailingAndAllRead) {
  std::string bytes;
  AppendSection(SomePoints(3), bytes);
  bytes += std::string(10000, 'x');  // more than the reader's scratch buffer
  Pipe pipe;
  std::vector<Point3f> points;
  HelperOutputReader reader(1 << 20);
  reader.Add(&points);
  EXPECT_FALSE(FeedInPieces(bytes, 5000, pipe, reader));
  EXPECT_EQ(reader.state(), HelperOutputReader::State::kTrailing);
  EXPECT_EQ(reader.bytes_read(), bytes.size());
}

TEST(HelperOutputReader, ACountPastTheLimitSizesNothing) {
  std::string bytes;
  const uint64_t count = uint64_t{1} << 40;  // 12 TB of points
  bytes.append(reinterpret_cast<const char*>(&count), sizeof count);
  bytes += std::string(100, '\0');
  Pipe pipe;
  std::vector<Point3f> points;
  HelperOutputReader reader(/*max_section_bytes=*/1 << 20);
  reader.Add(&points);
  EXPECT_FALSE(FeedInPieces(bytes, 16, pipe, reader));
  EXPECT_EQ(reader.state(), HelperOutputReader::State::kTooLarge);
  EXPECT_TRUE(points.empty());
  EXPECT_EQ(reader.bytes_read(), bytes.size()) << "what follows is read and dropped";
  // The limit is on the section's bytes: 12 bytes a point.
  HelperOutputReader at_limit(12 * 10);
  std::vector<Point3f> ten;
  at_limit.Add(&ten);
  std::string fits;
  AppendSection(SomePoints(10), fits);
  Pipe another;
  FeedInPieces(fits, 4096, another, at_limit);
  EXPECT_EQ(at_limit.state(), HelperOutputReader::State::kComplete);
}

TEST(HelperOutputReader, ReadsALargeSectionFromAWriterThatBlocks) {
  // 4 MB through a 64 KB pipe: the writer blocks until the reader drains.
  const std::vector<Point3f> points = SomePoints(350'000);
  std::string bytes;
  AppendSection(points, bytes);
  Pipe pipe;
  std::thread writer([&] {
    size_t at = 0;
    while (at < bytes.size()) {
      const ssize_t n = write(pipe.write_end, bytes.data() + at, bytes.size() - at);
      ASSERT_GT(n, 0);
      at += static_cast<size_t>(n);
    }
    pipe.CloseWriteEnd();
  });
  std::vector<Point3f> read_points;
  HelperOutputReader reader(uint64_t{1} << 30);
  reader.Add(&read_points);
  bool open = true;
  while (open) {
    pollfd readable{pipe.read_end, POLLIN, 0};
    ASSERT_EQ(poll(&readable, 1, 60'000), 1);
    open = reader.Drain(pipe.read_end);
  }
  writer.join();
  EXPECT_EQ(reader.state(), HelperOutputReader::State::kComplete);
  EXPECT_EQ(read_points, points);
}

}  // namespace
}  // namespace membrane

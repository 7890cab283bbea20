// The Draco decoder child (core/io/decode_subprocess.h) as membraned runs it: a decode counts
// its progress to the end, and a decoder dies with the process that started it, so that a
// membraned killed outright leaves no decoder running on.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "core/base/progress_meter.h"
#include "core/io/decode_subprocess.h"
#include "tests/server/draco_upload.h"
#include "tests/support/scratch_dir.h"

namespace membrane::testing {
namespace {

TEST(DecodeSubprocess, ADecodedCloudEndsItsProgressAtOne) {
  const std::string upload = LosslessDracoCloud("sphere", 2000);
  ProgressMeter meter;
  DecodeLimits limits;
  limits.helper = {MEMBRANE_DECODE_BINARY};
  const absl::StatusOr<PointCloud> cloud =
      DecodeInSubprocess(upload, limits, CancelToken::Never(), ProgressRange(&meter));
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_EQ(cloud->points.size(), 2000u);
  EXPECT_EQ(meter.fraction(), std::optional<double>(1.0));
}

TEST(DecodeSubprocess, ARefusedUploadDoesNotEndItsProgress) {
  ProgressMeter meter;
  DecodeLimits limits;
  limits.helper = {MEMBRANE_DECODE_BINARY};
  const absl::StatusOr<PointCloud> cloud = DecodeInSubprocess(
      std::string(100, 'x'), limits, CancelToken::Never(), ProgressRange(&meter));
  EXPECT_EQ(cloud.status().code(), absl::StatusCode::kInvalidArgument) << cloud.status();
  ASSERT_TRUE(meter.fraction().has_value());
  EXPECT_LE(*meter.fraction(), 0.9);
}

// A decoder that reads its input whole, then answers with `output` and succeeds: what a
// decoder gone wrong could write.
std::string WriteDecoderAnswering(const ScratchDir& dir, const std::string& output) {
  const std::string answer = dir.File("answer.bin");
  std::ofstream(answer, std::ios::binary) << output;
  const std::string script = dir.File("answering-decode.sh");
  std::ofstream out(script);
  out << "#!/bin/sh\ncat > /dev/null\ncat '" << answer << "'\n";
  out.close();
  EXPECT_EQ(chmod(script.c_str(), 0700), 0) << script;
  return script;
}

// The helper's output for a count and that many points, then `extra` bytes, less `short_by`.
std::string PointAnswer(uint64_t count, uint64_t points, size_t extra, size_t short_by = 0) {
  std::string out(reinterpret_cast<const char*>(&count), sizeof count);
  for (uint64_t i = 0; i < points; ++i) {
    const float p[3] = {1.0f * i, 2.0f, 3.0f};
    out.append(reinterpret_cast<const char*>(p), sizeof p);
  }
  out += std::string(extra, 'x');
  out.resize(out.size() - short_by);
  return out;
}

// The status of decoding a small upload with a decoder that answers `output`.
absl::Status DecodeAnswering(const std::string& output, int64_t memory_bytes = 1LL << 30) {
  ScratchDir dir;
  DecodeLimits limits;
  limits.helper = {WriteDecoderAnswering(dir, output)};
  limits.memory_bytes = memory_bytes;
  return DecodeInSubprocess(LosslessDracoCloud("sphere", 200), limits, CancelToken::Never())
      .status();
}

TEST(DecodeSubprocess, TheDecodersAnswerIsReadWholeAndNoFurther) {
  ScratchDir dir;
  DecodeLimits limits;
  limits.helper = {WriteDecoderAnswering(dir, PointAnswer(3, 3, 0))};
  const absl::StatusOr<PointCloud> cloud =
      DecodeInSubprocess(LosslessDracoCloud("sphere", 200), limits, CancelToken::Never());
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  ASSERT_EQ(cloud->points.size(), 3u);
  EXPECT_EQ(cloud->points[2], (Point3f{2.0f, 2.0f, 3.0f}));

  const absl::Status truncated = DecodeAnswering(PointAnswer(3, 3, 0, /*short_by=*/1));
  EXPECT_EQ(truncated.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(truncated.message(), "the Draco decoder returned a truncated point list");
  const absl::Status trailing = DecodeAnswering(PointAnswer(3, 3, 1));
  EXPECT_EQ(trailing.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(trailing.message(), "the Draco decoder returned bytes after its point list");
  // 2^36 points would be 768 GB: refused at the count, over the decoder's 1 GB.
  const absl::Status too_large = DecodeAnswering(PointAnswer(uint64_t{1} << 36, 3, 0));
  EXPECT_EQ(too_large.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(too_large.message(), "the Draco decoder returned a point list over its memory limit");
}

// The decoder in the next test: it writes its pid into a FIFO (the open waits for the test to
// read it), then waits for a line that never comes on a FIFO it holds open itself: a decoder
// that would run for ever.
std::string WriteEndlessDecoder(const ScratchDir& dir, const std::string& pid_fifo) {
  const std::string script = dir.File("endless-decode.sh");
  const std::string never = dir.File("never.fifo");
  EXPECT_EQ(mkfifo(never.c_str(), 0600), 0) << std::strerror(errno);
  std::ofstream out(script);
  out << "#!/bin/sh\necho $$ > '" << pid_fifo << "'\nexec 3<>'" << never
      << "'\nread line <&3\n";
  out.close();
  EXPECT_EQ(chmod(script.c_str(), 0700), 0) << script;
  return script;
}

// The pid the decoder writes into `fifo`, waited for up to 60 s; -1 when none comes. Opened
// without waiting, the FIFO shows no hangup before a writer has come.
pid_t ReadPid(const std::string& fifo) {
  const int fd = open(fifo.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return -1;
  std::string text;
  for (;;) {
    pollfd readable{fd, POLLIN, 0};
    if (poll(&readable, 1, 60'000) != 1) break;
    char buffer[32];
    const ssize_t n = read(fd, buffer, sizeof buffer);
    if (n <= 0) break;  // the writer is done
    text.append(buffer, static_cast<size_t>(n));
  }
  close(fd);
  return text.empty() ? -1 : std::atoi(text.c_str());
}

TEST(DecodeSubprocess, TheDecoderDiesWithTheProcessThatStartedIt) {
  ScratchDir dir;
  const std::string pid_fifo = dir.File("decoder.pid");
  ASSERT_EQ(mkfifo(pid_fifo.c_str(), 0600), 0) << std::strerror(errno);
  DecodeLimits limits;
  limits.helper = {WriteEndlessDecoder(dir, pid_fifo)};
  limits.timeout_seconds = 600;
  const std::string upload = LosslessDracoCloud("sphere", 2000);

  // The process that stands for membraned: it starts the decoder and waits for it.
  const pid_t parent = fork();
  ASSERT_GE(parent, 0) << std::strerror(errno);
  if (parent == 0) {
    (void)DecodeInSubprocess(upload, limits, CancelToken::Never());
    _exit(0);
  }
  const pid_t decoder = ReadPid(pid_fifo);
  ASSERT_GT(decoder, 0);
  // A pidfd of the decoder, which is not the test's child: readable once the decoder exits.
  const int pidfd = static_cast<int>(syscall(SYS_pidfd_open, decoder, 0));
  ASSERT_GE(pidfd, 0) << std::strerror(errno);

  ASSERT_EQ(kill(parent, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(waitpid(parent, &status, 0), parent);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);

  pollfd exited{pidfd, POLLIN, 0};
  const int ready = poll(&exited, 1, 60'000);
  EXPECT_EQ(ready, 1) << "the decoder " << decoder << " still runs 60 s after its parent died";
  if (ready != 1) kill(decoder, SIGKILL);
  close(pidfd);
}

}  // namespace
}  // namespace membrane::testing

#include "tests/server/gated_decoder.h"

#include <errno.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "absl/time/clock.h"
#include "absl/time/time.h"

namespace membrane::testing {
namespace {

int LineCount(const std::string& path) {
  std::ifstream in(path);
  return static_cast<int>(std::count(std::istreambuf_iterator<char>(in),
                                     std::istreambuf_iterator<char>(), '\n'));
}

}  // namespace

GatedDecoder::GatedDecoder(const ScratchDir& dir, const std::string& decoder)
    : script_(dir.File("gated-decode.sh")),
      gate_(dir.File("decode.gate")),
      arrivals_(dir.File("decode.arrivals")) {
  EXPECT_EQ(mkfifo(gate_.c_str(), 0600), 0) << gate_ << ": " << std::strerror(errno);
  // Read-write: the open does not wait for another end, and a line written before any decode
  // reads it stays in the FIFO.
  gate_fd_ = open(gate_.c_str(), O_RDWR | O_CLOEXEC);
  EXPECT_GE(gate_fd_, 0) << gate_ << ": " << std::strerror(errno);
  std::ofstream out(script_);
  out << "#!/bin/sh\nexec 3<>'" << gate_ << "'\necho arrived >> '" << arrivals_
      << "'\nread line <&3\nexec 3<&-\nexec '" << decoder << "' \"$@\"\n";
  out.close();
  EXPECT_TRUE(out) << script_;
  EXPECT_EQ(chmod(script_.c_str(), 0700), 0) << script_;
}

GatedDecoder::~GatedDecoder() {
  if (gate_fd_ < 0) return;
  // A decode whose server was killed outright is orphaned at the gate and would wait for
  // ever: a line for every decode that arrived lets each go on, to find its input closed.
  for (int i = Decodes(); i > 0; --i) {
    if (write(gate_fd_, "go\n", 3) != 3) break;
  }
  close(gate_fd_);
}

int GatedDecoder::Decodes() const { return LineCount(arrivals_); }

bool GatedDecoder::WaitForDecodes(int count, double seconds) const {
  const absl::Time end = absl::Now() + absl::Seconds(seconds);
  while (Decodes() < count) {
    if (absl::Now() > end) return false;
    absl::SleepFor(absl::Milliseconds(10));
  }
  return true;
}

void GatedDecoder::Open() const {
  ASSERT_GE(gate_fd_, 0) << gate_;
  // A pipe's buffer takes thousands of these lines: the write never waits.
  EXPECT_EQ(write(gate_fd_, "go\n", 3), 3) << gate_ << ": " << std::strerror(errno);
}

}  // namespace membrane::testing

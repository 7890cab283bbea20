// What a client sent, as logs and statuses quote it: bounded and with its control bytes
// escaped (server/client_text.h, server/server_log.h).
#include <string>

#include <gtest/gtest.h>

#include "server/client_text.h"
#include "server/server_log.h"

namespace membrane::testing {
namespace {

using server::ClientText;
using server::kClientTextBytes;

TEST(ClientTextTest, PrintableTextIsKeptAsItIs) {
  EXPECT_EQ(ClientText("membraned-0.0123456789abcdef"), "membraned-0.0123456789abcdef");
  EXPECT_EQ(ClientText("two words 'quoted'"), "two words 'quoted'");
}

TEST(ClientTextTest, ControlBytesBackslashAndNonAsciiAreEscaped) {
  EXPECT_EQ(ClientText(std::string("a\x1b[2Jb\0c\n\x7f\\", 11)), "a\\x1b[2Jb\\x00c\\x0a\\x7f\\\\");
  EXPECT_EQ(ClientText("\xc3\xa9"), "\\xc3\\xa9");
}

TEST(ClientTextTest, LongTextIsCutSayingItsLength) {
  const std::string schedule(3 << 20, 'h');
  const std::string quoted = ClientText(schedule);
  EXPECT_EQ(quoted, std::string(kClientTextBytes, 'h') + "...(3145728 bytes)");
  // The worst case, every byte escaped, stays within the bound the header states.
  const std::string escaped = ClientText(std::string(1 << 20, '\x1b'));
  EXPECT_LE(escaped.size(), 4 * kClientTextBytes + 24);
  EXPECT_EQ(escaped.rfind("\\x1b\\x1b", 0), 0u);
}

// The log line of a value holding a whole upload's worth of hostile bytes: one line, cut,
// nothing that moves a terminal's cursor.
TEST(ServerLogTest, ValuesAreCutAndTheirControlBytesEscaped) {
  std::string hostile = std::string("x\x1b[31mred\0\r\nnext", 16) + std::string(1 << 20, 'y');
  ::testing::internal::CaptureStderr();
  server::LogEvent("upload_rejected", {{"message", hostile}, {"peer", "ipv4:127.0.0.1:5"}});
  const std::string line = ::testing::internal::GetCapturedStderr();
  EXPECT_LT(line.size(), 2200u) << line.size();
  ASSERT_FALSE(line.empty());
  EXPECT_EQ(line.find('\n'), line.size() - 1) << line;
  for (const char ch : line.substr(0, line.size() - 1)) {
    EXPECT_GE(static_cast<unsigned char>(ch), 0x20) << line;
  }
  EXPECT_NE(line.find("message=\"x\\x1b[31mred\\x00\\x0d next"), std::string::npos) << line;
  EXPECT_NE(line.find("...(1048592 bytes)\" peer=ipv4:127.0.0.1:5\n"), std::string::npos)
      << line.substr(line.size() - 80);
}

TEST(ServerLogTest, PlainValuesStayUnquoted) {
  ::testing::internal::CaptureStderr();
  server::LogEvent("job_accepted", {{"job", "0123abcd"}, {"note", "two words"}, {"empty", ""}});
  const std::string line = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(line.find(" event=job_accepted job=0123abcd note=\"two words\" empty=\"\"\n"),
            std::string::npos)
      << line;
}

}  // namespace
}  // namespace membrane::testing

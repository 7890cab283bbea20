// ReadTokenFile: the shared secret of membraned --token-file and membrane --token-file.
#include "core/io/token_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/io_test_util.h"
#include "tests/support/scratch_dir.h"

namespace membrane::testing {
namespace {

using ::testing::HasSubstr;

TEST(TokenFileTest, FirstLineWithoutSurroundingWhitespace) {
  const ScratchDir scratch;
  const std::string path = scratch.File("token");
  WriteTestFile(path, "  s3cr3t-TOKEN_1\t\r\nsecond line ignored\n");
  absl::StatusOr<std::string> token = ReadTokenFile(path);
  ASSERT_TRUE(token.ok()) << token.status();
  EXPECT_EQ(*token, "s3cr3t-TOKEN_1");
}

TEST(TokenFileTest, EmptyOrBlankFirstLineIsRefused) {
  const ScratchDir scratch;
  const std::string path = scratch.File("token");
  WriteTestFile(path, " \nnot-the-first-line\n");
  absl::StatusOr<std::string> token = ReadTokenFile(path);
  EXPECT_EQ(token.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(std::string(token.status().message()), HasSubstr(path + " holds no token"));
}

TEST(TokenFileTest, InnerSpaceOrControlByteIsRefused) {
  const ScratchDir scratch;
  const std::string dir = scratch.path();
  WriteTestFile(dir + "/space", "two words\n");
  WriteTestFile(dir + "/control", std::string("a\x01" "b\n"));
  WriteTestFile(dir + "/utf8", "caf\xc3\xa9\n");
  for (const char* name : {"/space", "/control", "/utf8"}) {
    absl::StatusOr<std::string> token = ReadTokenFile(dir + name);
    EXPECT_EQ(token.status().code(), absl::StatusCode::kInvalidArgument) << name;
    EXPECT_THAT(std::string(token.status().message()), HasSubstr("non-printable")) << name;
  }
}

TEST(TokenFileTest, MissingFileIsInvalidArgumentNamingIt) {
  const ScratchDir scratch;
  const std::string path = scratch.File("absent");
  absl::StatusOr<std::string> token = ReadTokenFile(path);
  EXPECT_EQ(token.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(std::string(token.status().message()), HasSubstr(path));
}

}  // namespace
}  // namespace membrane::testing

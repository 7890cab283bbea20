// membraned --token-file: the shared-token file, a file of named clients, and a directory of
// them (server/client_tokens.h).
#include "server/client_tokens.h"

#include <unistd.h>

#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/io/file_bytes.h"
#include "tests/support/scratch_dir.h"

namespace membrane::testing {
namespace {

using server::ClientToken;
using server::ReadClientTokens;
using ::testing::HasSubstr;

class ClientTokensTest : public ::testing::Test {
 protected:
  std::string Write(const std::string& name, const std::string& text) {
    const std::string path = dir_.File(name);
    EXPECT_TRUE(WriteFileBytes(path, text).ok()) << path;
    return path;
  }
  ScratchDir dir_;
};

TEST_F(ClientTokensTest, OneBareTokenIsTheClientNamedAfterItsFile) {
  const auto clients = ReadClientTokens(Write("station-7", "  s3cret-token\nignored line\n"));
  ASSERT_TRUE(clients.ok()) << clients.status();
  ASSERT_EQ(clients->size(), 1u);
  EXPECT_EQ((*clients)[0].name, "station-7");
  EXPECT_EQ((*clients)[0].token, "s3cret-token");
  EXPECT_FALSE((*clients)[0].is_operator);
  const auto odd = ReadClientTokens(Write("my token.txt", "abc\n"));
  ASSERT_TRUE(odd.ok()) << odd.status();
  EXPECT_EQ((*odd)[0].name, "token");
}

TEST_F(ClientTokensTest, NamedClientsOnePerLineWithOperators) {
  const auto clients = ReadClientTokens(Write("clients", "# scanning floor\n"
                                                         "alice  tok-a\n"
                                                         "\n"
                                                         "bob\ttok-b\n"
                                                         "ops tok-o operator\n"));
  ASSERT_TRUE(clients.ok()) << clients.status();
  ASSERT_EQ(clients->size(), 3u);
  EXPECT_EQ((*clients)[1].name, "bob");
  EXPECT_EQ((*clients)[1].token, "tok-b");
  EXPECT_FALSE((*clients)[1].is_operator);
  EXPECT_EQ((*clients)[2].name, "ops");
  EXPECT_TRUE((*clients)[2].is_operator);
}

// As Kubernetes mounts a secret: a file per key, beside its own dot-named links and directory.
TEST_F(ClientTokensTest, DirectoryIsReadFileByFile) {
  std::filesystem::create_directory(dir_.File("secret"));
  std::filesystem::create_directory(dir_.File("secret/..2026_12_02"));
  Write("secret/..2026_12_02/alice", "tok-a\n");
  ASSERT_EQ(symlink("..2026_12_02/alice", dir_.File("secret/alice").c_str()), 0);
  Write("secret/operators", "ops tok-o operator\n");
  Write("secret/.hidden", "tok-h\n");
  const auto clients = ReadClientTokens(dir_.File("secret"));
  ASSERT_TRUE(clients.ok()) << clients.status();
  ASSERT_EQ(clients->size(), 2u);
  EXPECT_EQ((*clients)[0].name, "alice");
  EXPECT_EQ((*clients)[0].token, "tok-a");
  EXPECT_EQ((*clients)[1].name, "ops");
  EXPECT_TRUE((*clients)[1].is_operator);
}

TEST_F(ClientTokensTest, MistakesAreRefusedNamingTheFile) {
  const struct {
    const char* text;
    const char* message;
  } cases[] = {
      {"\n# nothing\n", "holds no token"},
      {"alice tok-a\nalice tok-b\n", "the client name 'alice' is given twice"},
      {"alice tok\nbob tok\n", "client 'bob' has the token of another"},
      {"alice tok-a admin\n", "line 1 is not \"NAME TOKEN\" or \"NAME TOKEN operator\""},
      {"alice tok-a\nbob\n", "line 2 is not"},
      {"al/ice tok-a\n", "the client name must be"},
      {"alice tok\x01\n", "holds a non-printable character"},
  };
  for (const auto& c : cases) {
    const std::string path = Write("bad", c.text);
    const auto clients = ReadClientTokens(path);
    ASSERT_FALSE(clients.ok()) << c.text;
    EXPECT_EQ(clients.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_THAT(clients.status().message(), HasSubstr(path)) << c.text;
    EXPECT_THAT(clients.status().message(), HasSubstr(c.message)) << c.text;
  }
  std::filesystem::create_directory(dir_.File("empty"));
  EXPECT_THAT(ReadClientTokens(dir_.File("empty")).status().message(),
              HasSubstr("holds no token"));
  EXPECT_FALSE(ReadClientTokens(dir_.File("missing")).ok());
}

}  // namespace
}  // namespace membrane::testing

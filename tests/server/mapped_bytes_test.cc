#include "server/mapped_bytes.h"

#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

#include "absl/strings/str_cat.h"
#include "core/base/malloc_policy.h"
#include "gtest/gtest.h"
#include "tests/server/every_mapping.h"

namespace membrane::server {
namespace {

// Whether [data, data + size) lies in one mapping of /proc/self/maps other than the heap.
bool InAMappingOtherThanTheHeap(const char* data, size_t size) {
  std::ifstream maps("/proc/self/maps");
  std::string line;
  const auto begin = reinterpret_cast<uintptr_t>(data);
  while (std::getline(maps, line)) {
    std::istringstream fields(line);
    std::string range;
    fields >> range;
    const size_t dash = range.find('-');
    const uintptr_t from = std::stoull(range.substr(0, dash), nullptr, 16);
    const uintptr_t to = std::stoull(range.substr(dash + 1), nullptr, 16);
    if (begin >= from && begin + size <= to) return line.find("[heap]") == std::string::npos;
  }
  return false;
}

TEST(MappedBytes, AppendsKeepTheirOrderAsTheMappingGrows) {
  MappedBytes bytes;
  EXPECT_TRUE(bytes.empty());
  EXPECT_FALSE(bytes.mapped());
  std::string expected;
  for (int i = 0; i < 20000; ++i) {  // about 200 KB: the mapping grows many times
    const std::string piece = absl::StrCat("event ", i, i % 7 == 0 ? std::string(40, 'x') : "");
    bytes.Append(piece);
    expected += piece;
  }
  EXPECT_TRUE(bytes.mapped());
  EXPECT_EQ(bytes.size(), expected.size());
  EXPECT_EQ(bytes.view(), expected);
  EXPECT_TRUE(InAMappingOtherThanTheHeap(bytes.view().data(), bytes.size()));
}

TEST(MappedBytes, ExtendGivesRoomThatStays) {
  MappedBytes bytes;
  bytes.Append("ab");
  char* room = bytes.Extend(3);
  room[0] = 'c';
  room[1] = 'd';
  room[2] = 'e';
  bytes.Append(std::string(10000, 'f'));  // moves the mapping, with what it holds
  EXPECT_EQ(bytes.view().substr(0, 6), "abcdef");
  EXPECT_EQ(bytes.size(), 10005u);
}

TEST(MappedBytes, AMoveTakesTheBytes) {
  MappedBytes from;
  from.Append("kept bytes");
  MappedBytes to(std::move(from));
  EXPECT_EQ(to.view(), "kept bytes");
  EXPECT_TRUE(from.empty());  // NOLINT(bugprone-use-after-move): a moved-from log is empty
  MappedBytes other;
  other.Append("old");
  other = std::move(to);
  EXPECT_EQ(other.view(), "kept bytes");
  other.Append(", more");
  EXPECT_EQ(other.view(), "kept bytes, more");
}

// In a child process: takes every mapping the kernel allows (vm.max_map_count), then appends
// to a new MappedBytes and to one that had one page mapped (and no room to grow it in place).
// Exits 0 when both hold their bytes in the heap, 1 when one kept a mapping, 2 when the
// contents differ, 3 when the limit was not reached.
[[noreturn]] void AppendWithNoMappingLeftAndExit() {
  MappedBytes grown;
  grown.Append("before the limit;");
  if (!grown.mapped()) std::_Exit(1);
  const long page = 4096;
  // A page right after its one page, so that it cannot grow in place.
  void* after = const_cast<char*>(grown.view().data()) + page;
  mmap(after, page, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_FIXED_NOREPLACE, -1, 0);
  if (!TakeEveryMappingLeft()) std::_Exit(3);
  const std::string more(3 * page, 'm');
  MappedBytes fresh;
  fresh.Append(more);
  grown.Append(more);  // then unmaps its page: the first of the two to append takes no slot
  if (grown.mapped() || fresh.mapped()) std::_Exit(1);
  if (grown.view() != "before the limit;" + more || fresh.view() != more) std::_Exit(2);
  grown.Append("after");
  std::_Exit(grown.view() == "before the limit;" + more + "after" ? 0 : 2);
}

TEST(MappedBytes, WithNoMappingLeftTheBytesMoveToTheHeap) {
  if (!kGlibcMalloc) GTEST_SKIP() << "the sanitizers' allocators need mappings of their own";
  EXPECT_EXIT(AppendWithNoMappingLeftAndExit(), ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace membrane::server

// The memory a process may use, read from /proc/meminfo and the cgroup files: the default of
// membraned's memory budget and of `membrane reconstruct --local`'s memory limit. Each test
// builds the files in a scratch tree, as a machine, a v1 container and a v2 container lay
// them out.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "core/pipeline/machine_memory.h"
#include "tests/support/scratch_dir.h"

namespace membrane::testing {
namespace {

constexpr char kMemInfo[] =
    "MemTotal:       24683584 kB\n"
    "MemFree:        19000000 kB\n"
    "MemAvailable:   20000000 kB\n"
    "Buffers:          100000 kB\n";

// A machine's files under a scratch directory.
class MachineFiles {
 public:
  MachineFiles() {
    files_.meminfo = dir_.File("meminfo");
    files_.self_cgroup = dir_.File("self_cgroup");
    files_.cgroup_root = dir_.File("cgroup");
  }
  // Writes `text` to `path` below the scratch directory, creating its directories.
  void Write(const std::string& path, const std::string& text) const {
    const std::filesystem::path full = dir_.File(path);
    std::filesystem::create_directories(full.parent_path());
    std::ofstream(full) << text;
  }
  const MachineMemoryFiles& files() const { return files_; }

 private:
  ScratchDir dir_;
  MachineMemoryFiles files_;
};

TEST(MemInfoBytes, ReadsKibibyteLinesAndRefusesOthers) {
  EXPECT_EQ(MemInfoBytes(kMemInfo, "MemTotal"), int64_t{24683584} * 1024);
  EXPECT_EQ(MemInfoBytes(kMemInfo, "MemAvailable"), int64_t{20000000} * 1024);
  EXPECT_EQ(MemInfoBytes(kMemInfo, "SwapTotal"), std::nullopt);
  EXPECT_EQ(MemInfoBytes("MemTotal: lots kB\n", "MemTotal"), std::nullopt);
  EXPECT_EQ(MemInfoBytes("MemTotal: 1000\n", "MemTotal"), std::nullopt);  // no unit
  EXPECT_EQ(MemInfoBytes("MemTotal: -5 kB\n", "MemTotal"), std::nullopt);
  // "MemTotalX" is another key, not MemTotal.
  EXPECT_EQ(MemInfoBytes("MemTotalX: 5 kB\n", "MemTotal"), std::nullopt);
}

TEST(CgroupBytes, MaxAndHugeValuesAreNoLimit) {
  EXPECT_EQ(CgroupBytes("2147483648\n"), int64_t{2147483648});
  EXPECT_EQ(CgroupBytes("max\n"), std::nullopt);
  EXPECT_EQ(CgroupBytes("9223372036854771712\n"), std::nullopt);  // v1's "unlimited"
  EXPECT_EQ(CgroupBytes(""), std::nullopt);
  EXPECT_EQ(CgroupBytes("12x"), std::nullopt);
}

TEST(ReadMachineMemory, WithoutCgroupLimitsTheMachineCounts) {
  MachineFiles m;
  m.Write("meminfo", kMemInfo);
  m.Write("self_cgroup", "4:memory:/user.slice\n0::/user.slice\n");
  m.Write("cgroup/memory/user.slice/memory.limit_in_bytes", "9223372036854771712\n");
  const MachineMemory got = ReadMachineMemory(m.files());
  EXPECT_EQ(got.total_bytes, int64_t{24683584} * 1024);
  EXPECT_EQ(got.available_bytes, int64_t{20000000} * 1024);
  EXPECT_EQ(got.total_source, "MemTotal");
}

TEST(ReadMachineMemory, TheLowestCgroupV1LimitOnThePathBinds) {
  MachineFiles m;
  m.Write("meminfo", kMemInfo);
  m.Write("self_cgroup", "9:cpu,cpuacct:/a/b\n4:memory:/a/b\n0::/\n");
  m.Write("cgroup/memory/a/b/memory.limit_in_bytes", "8000000000\n");
  m.Write("cgroup/memory/a/memory.limit_in_bytes", "3000000000\n");  // the parent's binds
  m.Write("cgroup/memory/memory.limit_in_bytes", "9223372036854771712\n");
  const MachineMemory got = ReadMachineMemory(m.files());
  EXPECT_EQ(got.total_bytes, 3000000000);
  EXPECT_EQ(got.available_bytes, 3000000000);
  EXPECT_EQ(got.total_source, "cgroup /a");
}

TEST(ReadMachineMemory, ANamespacedCgroupV2ContainerReadsTheMountsRoot) {
  MachineFiles m;
  m.Write("meminfo", kMemInfo);
  // The container sees its own cgroup as "/" and its limit at the root of the mount.
  m.Write("self_cgroup", "0::/\n");
  m.Write("cgroup/memory.max", "2147483648\n");
  const MachineMemory got = ReadMachineMemory(m.files());
  EXPECT_EQ(got.total_bytes, 2147483648);
  EXPECT_EQ(got.available_bytes, 2147483648);
  EXPECT_EQ(got.total_source, "cgroup /");
}

TEST(ReadMachineMemory, AHostPathMissingFromTheMountFallsBackToItsRoot) {
  MachineFiles m;
  m.Write("meminfo", kMemInfo);
  m.Write("self_cgroup", "0::/kubepods/pod1/c1\n");
  m.Write("cgroup/memory.max", "max\n");
  m.Write("cgroup/kubepods/memory.max", "1000000000\n");
  const MachineMemory got = ReadMachineMemory(m.files());
  EXPECT_EQ(got.total_bytes, 1000000000);
  EXPECT_EQ(got.total_source, "cgroup /kubepods");
}

TEST(ReadMachineMemory, AvailableIsMemAvailableWhenBelowTheLimit) {
  MachineFiles m;
  m.Write("meminfo", "MemTotal: 4000000 kB\nMemAvailable: 1000000 kB\n");
  m.Write("self_cgroup", "0::/\n");
  m.Write("cgroup/memory.max", "3000000000\n");
  const MachineMemory got = ReadMachineMemory(m.files());
  EXPECT_EQ(got.total_bytes, 3000000000);
  EXPECT_EQ(got.available_bytes, 1024000000);
}

TEST(ReadMachineMemory, MissingFilesGiveUnknownNotAnError) {
  MachineFiles m;
  const MachineMemory got = ReadMachineMemory(m.files());
  EXPECT_EQ(got.total_bytes, 0);
  EXPECT_EQ(got.available_bytes, 0);
  EXPECT_EQ(got.total_source, "unknown");
}

TEST(ReadMachineMemory, ThisMachineHasSomeMemory) {
  const MachineMemory got = ReadMachineMemory();
  EXPECT_GT(got.total_bytes, 0);
  EXPECT_GT(got.available_bytes, 0);
  EXPECT_LE(got.available_bytes, got.total_bytes);
}

}  // namespace
}  // namespace membrane::testing

// bench_upload_parts: the upload's Draco work, one cloud against parts (core/io/draco_parts.h),
// on the cloud of a file: the read, then per (parts, threads) the encode the client makes and
// the decode the server's child makes (the same code, here in process), wall and process CPU
// seconds (medians of interleaved repetitions), and the bytes. With --helper PATH (a
// membrane-decode binary) also the decode as membraned runs it, in the child
// (DecodeInSubprocess): wall, this process's CPU and the child's. The positions are quantized on
// one box over the cloud (BoundingGrid, the way the client's snap grid is), so that every way
// decodes to the same points: checked on the first repetition (sorted points against one
// part's); exit status 1 when they differ.
//   bench_upload_parts CLOUD [--bits 14] [--parts 1,8] [--threads 1,2] [--repeats 3]
//                      [--helper PATH]
#include <sys/resource.h>
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "absl/strings/numbers.h"
#include "core/base/cancel_token.h"
#include "core/io/decode_subprocess.h"
#include "core/io/draco_parts.h"
#include "core/io/point_cloud_io.h"
#include "tests/bench/bench_util.h"

namespace membrane::bench {
namespace {

struct Way {
  int parts = 1;
  int threads = 1;
  std::vector<double> encode_wall, encode_cpu, decode_wall, decode_cpu;
  std::vector<double> child_wall, child_cpu, child_parent_cpu;  // with --helper
  size_t bytes = 0;
};

// CPU seconds of this process's waited-for children so far.
double ChildrenCpuSeconds() {
  rusage usage{};
  getrusage(RUSAGE_CHILDREN, &usage);
  return usage.ru_utime.tv_sec + usage.ru_stime.tv_sec +
         1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

// A list of positive integers (ParsePointCounts's syntax) as ints.
bool ParseInts(const std::string& value, std::vector<int>& out) {
  std::vector<int64_t> counts;
  if (!ParsePointCounts(value, counts)) return false;
  out.assign(counts.begin(), counts.end());
  return true;
}

std::vector<Point3f> Sorted(std::vector<Point3f> points) {
  std::sort(points.begin(), points.end());
  return points;
}

int Run(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_upload_parts CLOUD [--bits B] [--parts 1,8] "
                         "[--threads 1,2] [--repeats R] [--helper PATH]\n");
    return 2;
  }
  const std::string path = argv[1];
  int bits = 14, repeats = 3;
  std::vector<int> part_counts = {1, 8}, thread_counts = {1, 2};
  std::string helper;
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string flag = argv[i], value = argv[i + 1];
    bool ok = true;
    if (flag == "--bits") {
      ok = absl::SimpleAtoi(value, &bits) && bits >= 1 && bits <= 30;
    } else if (flag == "--parts") {
      ok = ParseInts(value, part_counts);
    } else if (flag == "--threads") {
      ok = ParseInts(value, thread_counts);
    } else if (flag == "--repeats") {
      ok = absl::SimpleAtoi(value, &repeats) && repeats >= 1;
    } else if (flag == "--helper") {
      helper = value;
    } else {
      ok = false;
    }
    if (!ok) {
      std::fprintf(stderr, "bench_upload_parts: bad %s %s\n", flag.c_str(), value.c_str());
      return 2;
    }
  }
  const double read_start = Now();
  absl::StatusOr<PointCloud> cloud = ReadPointCloud(path);
  if (!cloud.ok()) {
    std::fprintf(stderr, "bench_upload_parts: %s\n", std::string(cloud.status().message()).c_str());
    return 1;
  }
  std::printf("%s: %zu points, read in %.3f s; %d-bit positions on one box; load %s\n",
              path.c_str(), cloud->points.size(), Now() - read_start, bits,
              LoadAverage().c_str());
  DracoOptions options;
  options.position_quantization_bits = bits;
  options.box = BoundingGrid(cloud->points, bits).box;

  std::vector<Way> ways;
  for (int p : part_counts)
    for (int t : thread_counts) {
      if (p == 1 && t > 1 && thread_counts.front() == 1) continue;  // one part is one thread
      Way& way = ways.emplace_back();
      way.parts = p;
      way.threads = t;
    }
  std::vector<Point3f> reference;
  bool same = true;
  for (int r = 0; r < repeats; ++r) {
    for (Way& way : ways) {
      double wall = Now(), cpu = ClockSeconds(CLOCK_PROCESS_CPUTIME_ID);
      absl::StatusOr<DracoParts> encoded =
          EncodeDracoPointCloudParts(cloud->points, options, way.parts, way.threads);
      way.encode_wall.push_back(Now() - wall);
      way.encode_cpu.push_back(ClockSeconds(CLOCK_PROCESS_CPUTIME_ID) - cpu);
      if (!encoded.ok()) {
        std::fprintf(stderr, "encode: %s\n", std::string(encoded.status().message()).c_str());
        return 1;
      }
      way.bytes = encoded->bytes.size();
      const std::vector<uint64_t> part_bytes =
          encoded->part_bytes.size() > 1 ? encoded->part_bytes : std::vector<uint64_t>();
      wall = Now();
      cpu = ClockSeconds(CLOCK_PROCESS_CPUTIME_ID);
      absl::StatusOr<DecodedDracoCloud> decoded = DecodeDracoPointCloudParts(
          encoded->bytes, part_bytes, DracoMeshPolicy::kRejectMesh, way.threads);
      way.decode_wall.push_back(Now() - wall);
      way.decode_cpu.push_back(ClockSeconds(CLOCK_PROCESS_CPUTIME_ID) - cpu);
      if (!decoded.ok()) {
        std::fprintf(stderr, "decode: %s\n", std::string(decoded.status().message()).c_str());
        return 1;
      }
      std::vector<Point3f> in_process = std::move(decoded->cloud.points);
      if (!helper.empty()) {
        DecodeLimits limits;
        limits.helper = {helper};
        limits.threads = way.threads;
        limits.memory_bytes = int64_t{16} << 30;
        limits.timeout_seconds = 600;
        wall = Now();
        cpu = ClockSeconds(CLOCK_PROCESS_CPUTIME_ID);
        const double child_cpu = ChildrenCpuSeconds();
        absl::StatusOr<PointCloud> child =
            DecodeInSubprocess(encoded->bytes, limits, CancelToken::Never(), ProgressRange(),
                               part_bytes);
        way.child_wall.push_back(Now() - wall);
        way.child_parent_cpu.push_back(ClockSeconds(CLOCK_PROCESS_CPUTIME_ID) - cpu);
        way.child_cpu.push_back(ChildrenCpuSeconds() - child_cpu);
        if (!child.ok()) {
          std::fprintf(stderr, "child decode: %s\n", std::string(child.status().message()).c_str());
          return 1;
        }
        if (child->points != in_process) {
          std::printf("DIFFERENT POINTS from the child: %d parts on %d threads\n", way.parts,
                      way.threads);
          same = false;
        }
      }
      if (r == 0) {
        std::vector<Point3f> sorted = Sorted(std::move(in_process));
        if (reference.empty()) {
          reference = std::move(sorted);
        } else if (sorted != reference) {
          std::printf("DIFFERENT POINTS: %d parts on %d threads\n", way.parts, way.threads);
          same = false;
        }
      }
    }
  }
  std::printf("parts threads | encode wall s  CPU s | decode wall s  CPU s | bytes\n");
  for (Way& way : ways) {
    std::printf("%5d %7d | %13.3f %6.3f | %13.3f %6.3f | %d (%d parts)\n", way.parts, way.threads,
                Median(way.encode_wall), Median(way.encode_cpu), Median(way.decode_wall),
                Median(way.decode_cpu), static_cast<int>(way.bytes), way.parts);
  }
  if (!helper.empty()) {
    std::printf("in the child %s:\nparts threads | wall s | parent CPU s | child CPU s\n",
                helper.c_str());
    for (Way& way : ways) {
      std::printf("%5d %7d | %6.3f | %12.3f | %11.3f\n", way.parts, way.threads,
                  Median(way.child_wall), Median(way.child_parent_cpu), Median(way.child_cpu));
    }
  }
  std::printf("%s\n", same ? "every way decodes to the same points"
                           : "SOME WAYS DECODE TO OTHER POINTS");
  return same ? 0 : 1;
}

}  // namespace
}  // namespace membrane::bench

int main(int argc, char** argv) { return membrane::bench::Run(argc, argv); }

// bench_floods: the cave filling's flood from the array border (FloodFromBorder,
// core/mesh/border_flood.h) on 1 and on more threads, side by side: wall, process CPU (all
// threads) and calling-thread CPU seconds, medians of interleaved repetitions, on the
// eroded outside of a solid torus in an n^3 array (the cave filling's input on a torus cloud's
// grid: the outside is most of the array) with closed bubbles inside the torus that the flood
// must not reach. Checks that every thread count gives the one-thread bits; exit status 1
// when not.
//   bench_floods [--n 821] [--threads 1,2] [--repeats 5]
#include <time.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "absl/strings/numbers.h"
#include "absl/strings/str_split.h"
#include "core/engine/flat_bitset.h"
#include "core/mesh/border_flood.h"
#include "tests/bench/bench_util.h"

namespace membrane::bench {
namespace {

// Open: outside a torus of major radius 0.3 n and minor radius 0.12 n about the array's
// centre, and inside 8 balls of radius 0.04 n on its core circle.
FlatBitset TorusOutside(int n) {
  FlatBitset open(int64_t{n} * n * n);
  const double c = 0.5 * (n - 1), major = 0.3 * n, minor = 0.12 * n, bubble = 0.04 * n;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const double dx = x - c, dy = y - c, dz = z - c;
        const double ring = std::hypot(dx, dy) - major;
        bool is_open = ring * ring + dz * dz > minor * minor;
        for (int k = 0; k < 8 && !is_open; ++k) {
          const double a = k * M_PI / 4;
          const double bx = dx - major * std::cos(a), by = dy - major * std::sin(a);
          is_open = bx * bx + by * by + dz * dz < bubble * bubble;
        }
        if (is_open) open.set(x + int64_t{n} * (y + int64_t{n} * z));
      }
  return open;
}

int Main(int argc, char** argv) {
  int n = 821, repeats = 5;
  std::vector<int> thread_counts = {1, 2};
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--n" && absl::SimpleAtoi(argv[i + 1], &n)) continue;
    if (flag == "--repeats" && absl::SimpleAtoi(argv[i + 1], &repeats)) continue;
    if (flag == "--threads") {
      thread_counts.clear();
      for (absl::string_view t : absl::StrSplit(argv[i + 1], ',')) {
        int k = 0;
        if (absl::SimpleAtoi(t, &k)) thread_counts.push_back(k);
      }
      continue;
    }
    std::fprintf(stderr, "usage: bench_floods [--n 821] [--threads 1,2] [--repeats 5]\n");
    return 2;
  }
  const std::array<int, 3> dims = {n, n, n};
  const FlatBitset open = TorusOutside(n);
  std::printf("bench_floods: %d^3 array, %lld open voxels, load %s\n", n,
              static_cast<long long>(open.Count()), LoadAverage().c_str());
  std::vector<std::vector<double>> wall(thread_counts.size()), cpu(thread_counts.size()),
      caller(thread_counts.size());
  FlatBitset first;
  bool same = true;
  for (int r = 0; r < repeats; ++r)
    for (size_t k = 0; k < thread_counts.size(); ++k) {
      const double w0 = Now(), c0 = ClockSeconds(CLOCK_PROCESS_CPUTIME_ID),
                   t0 = ClockSeconds(CLOCK_THREAD_CPUTIME_ID);
      FlatBitset reached = FloodFromBorder(dims, open, thread_counts[k]);
      wall[k].push_back(Now() - w0);
      cpu[k].push_back(ClockSeconds(CLOCK_PROCESS_CPUTIME_ID) - c0);
      caller[k].push_back(ClockSeconds(CLOCK_THREAD_CPUTIME_ID) - t0);
      if (first.bits() == 0) {
        first = std::move(reached);
      } else if (std::memcmp(first.words(), reached.words(), first.word_count() * 8) != 0) {
        same = false;
      }
    }
  std::printf("reached %lld\n", static_cast<long long>(first.Count()));
  std::printf("threads  wall s (median)  cpu s  calling thread cpu s   (%d repeats)\n", repeats);
  for (size_t k = 0; k < thread_counts.size(); ++k)
    std::printf("%7d  %14.3f  %6.3f  %20.3f\n", thread_counts[k], Median(wall[k]), Median(cpu[k]),
                Median(caller[k]));
  std::printf("same bits for every thread count: %s\n", same ? "yes" : "NO");
  return same ? 0 : 1;
}

}  // namespace
}  // namespace membrane::bench

int main(int argc, char** argv) { return membrane::bench::Main(argc, argv); }

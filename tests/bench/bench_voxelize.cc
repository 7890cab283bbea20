// bench_voxelize: Voxelize (core/engine/voxelization.h) at the formula-(1) voxel on 1 and on
// more threads, side by side: wall and process CPU seconds (all threads), medians of
// interleaved repetitions, the calling thread's CPU seconds (the longest path), and the
// distinct-point count alone (formula (1)'s share). Then Voxelize as the pipeline calls it,
// after its grid planning: given the planned voxel, and given the planned voxel and the
// planned bounds (VoxelizeOptions::checked_bounds: no second point check), CPU seconds side by
// side, and the point check (CheckedBounds) alone. Checks that every thread count and every
// way gives the first one's grid; exit status 1 when not.
//   bench_voxelize [--points 1000000,4000000] [--threads 1,2] [--repeats 3] [--shape torus]
#include <time.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "core/engine/voxelization.h"
#include "core/synth/synthesize.h"
#include "tests/bench/bench_util.h"

namespace membrane::bench {
namespace {

// On a loaded machine a second thread rarely finds a free core, and the wall time hides what
// the threads share; the calling thread's own CPU time is the longest path whatever the load.
struct Times {
  std::vector<double> wall, cpu, caller_cpu, count_wall;
  // Given the planned voxel; given the planned voxel and bounds; the point check alone.
  std::vector<double> voxel_cpu, bounds_cpu, check_cpu;
};

// Process CPU seconds of `run`.
template <typename Run>
double CpuOf(const Run& run) {
  const double c = ClockSeconds(CLOCK_PROCESS_CPUTIME_ID);
  run();
  return ClockSeconds(CLOCK_PROCESS_CPUTIME_ID) - c;
}

int Run(int argc, char** argv) {
  std::vector<int64_t> counts = {1000000, 4000000};
  std::vector<int> threads = {1, 2};
  int repeats = 3;
  std::string shape = "torus";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i], value = argv[i + 1];
    bool ok = true;
    if (flag == "--points") {
      ok = ParsePointCounts(value, counts);
    } else if (flag == "--threads") {
      threads.clear();
      for (absl::string_view t : absl::StrSplit(value, ',')) {
        int n = 0;
        ok = ok && absl::SimpleAtoi(t, &n) && n >= 1;
        threads.push_back(n);
      }
    } else if (flag == "--repeats") {
      ok = absl::SimpleAtoi(value, &repeats) && repeats >= 1;
    } else if (flag == "--shape") {
      shape = value;
    } else {
      ok = false;
    }
    if (!ok) {
      std::fprintf(stderr, "usage: bench_voxelize [--points N,...] [--threads T,...] "
                           "[--repeats R] [--shape NAME]\n");
      return 2;
    }
  }
  bool same = true;
  for (const int64_t n : counts) {
    SynthOptions synth;
    synth.shape = shape;
    synth.points = n;
    absl::StatusOr<PointCloud> cloud = SynthesizeShape(synth);
    if (!cloud.ok()) {
      std::fprintf(stderr, "%s\n", std::string(cloud.status().message()).c_str());
      return 2;
    }
    std::vector<Times> times(threads.size());
    VoxelStates first;
    std::string grid;
    // The pipeline's grid planning (PlanGrid): the point check and formula (1), once.
    const absl::StatusOr<Box3d> bounds = CheckedBounds(cloud->points);
    if (!bounds.ok()) {
      std::fprintf(stderr, "%s\n", std::string(bounds.status().message()).c_str());
      return 2;
    }
    const double voxel = FormulaVoxelSize(*bounds, cloud->points);
    const auto check_grid = [&](const absl::StatusOr<Voxelization>& v, int t, const char* way) {
      if (v.ok() && v->grid.states() == first) return;
      same = false;
      std::printf("%s %lld points: %d threads, %s: another grid\n", shape.c_str(),
                  static_cast<long long>(n), t, way);
    };
    for (int r = 0; r < repeats; ++r)
      for (size_t k = 0; k < threads.size(); ++k) {
        double w = Now();
        DistinctPointCount(cloud->points, threads[k]);
        times[k].count_wall.push_back(Now() - w);
        w = Now();
        const double c = ClockSeconds(CLOCK_PROCESS_CPUTIME_ID);
        const double t = ClockSeconds(CLOCK_THREAD_CPUTIME_ID);
        absl::StatusOr<Voxelization> v =
            Voxelize(cloud->points, VoxelizeOptions{.threads = threads[k]});
        times[k].wall.push_back(Now() - w);
        times[k].cpu.push_back(ClockSeconds(CLOCK_PROCESS_CPUTIME_ID) - c);
        times[k].caller_cpu.push_back(ClockSeconds(CLOCK_THREAD_CPUTIME_ID) - t);
        if (!v.ok()) {
          std::fprintf(stderr, "%s\n", std::string(v.status().message()).c_str());
          return 2;
        }
        if (first.empty()) {
          first = v->grid.states();
          grid = absl::StrCat(v->grid.dim(0), "x", v->grid.dim(1), "x", v->grid.dim(2));
        } else if (v->grid.states() != first) {
          same = false;
          std::printf("%s %lld points: %d threads give another grid\n", shape.c_str(),
                      static_cast<long long>(n), threads[k]);
        }
        absl::StatusOr<Voxelization> planned = absl::UnknownError("not run");
        times[k].voxel_cpu.push_back(CpuOf([&] {
          planned = Voxelize(cloud->points, {.voxel_size = voxel, .threads = threads[k]});
        }));
        check_grid(planned, threads[k], "given the voxel");
        planned = absl::UnknownError("not run");
        times[k].bounds_cpu.push_back(CpuOf([&] {
          planned = Voxelize(cloud->points, {.voxel_size = voxel,
                                             .threads = threads[k],
                                             .checked_bounds = *bounds});
        }));
        check_grid(planned, threads[k], "given the voxel and bounds");
        planned = absl::UnknownError("not run");
        times[k].check_cpu.push_back(CpuOf([&] { (void)CheckedBounds(cloud->points); }));
      }
    for (size_t k = 0; k < threads.size(); ++k) {
      std::printf("%s %9lld points grid %-14s threads %d  voxelize %6.2f s wall %6.2f s cpu "
                  "%6.2f s caller cpu  (distinct count %5.2f s wall)  load %s\n",
                  shape.c_str(), static_cast<long long>(n), grid.c_str(), threads[k],
                  Median(times[k].wall), Median(times[k].cpu), Median(times[k].caller_cpu),
                  Median(times[k].count_wall), LoadAverage().c_str());
      // Paired: each repetition ran both ways back to back.
      std::vector<double> ratios;
      for (size_t r = 0; r < times[k].voxel_cpu.size(); ++r)
        ratios.push_back(times[k].bounds_cpu[r] / times[k].voxel_cpu[r]);
      std::printf("%s %9lld points planned: given the voxel %6.3f s cpu, the voxel and bounds "
                  "%6.3f s cpu (paired %.3fx; point check alone %6.3f s cpu)  threads %d\n",
                  shape.c_str(), static_cast<long long>(n), Median(times[k].voxel_cpu),
                  Median(times[k].bounds_cpu), Median(ratios), Median(times[k].check_cpu),
                  threads[k]);
    }
  }
  std::printf(same ? "grids identical for every thread count\n" : "GRIDS DIFFER\n");
  return same ? 0 : 1;
}

}  // namespace
}  // namespace membrane::bench

int main(int argc, char** argv) { return membrane::bench::Run(argc, argv); }

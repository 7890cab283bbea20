// bench_separation: the piece separation (SeparateDataPieces) alone, timed on the grid the
// generations leave, for the models where its cost was measured: the teapot class
// (teapot-scan-164: the teapot scan subsampled to a formula-(1) grid 164 voxels long), the
// torus at N million points (torus-NM) and the clouds of ../shared/data/clouds by name. The
// shrink runs once without its steps after the generations; at 4M points and more its grid is
// kept in --cache (states, one byte a voxel) and read back.
// Each repetition separates a copy of that grid and reports the calling thread's CPU seconds
// (the separation runs on it alone), the pieces and whether they were separated; the copies'
// states after the separation are compared (one checksum for all repetitions).
#include <time.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "core/base/cancel_token.h"
#include "core/engine/hard_voxel_points.h"
#include "core/engine/membrane_shrinker.h"
#include "core/engine/piece_separation.h"
#include "core/engine/voxelization.h"
#include "core/io/point_cloud_io.h"
#include "core/synth/synthesize.h"
#include "tests/bench/bench_clouds.h"
#include "tests/bench/bench_util.h"

namespace membrane {
namespace {
using bench::ClockSeconds;
using bench::LoadAverage;
using bench::Median;
using bench::SubsampleForGridSide;

uintmax_t FileSize(const std::string& path) {
  std::error_code ec;
  const uintmax_t size = std::filesystem::file_size(path, ec);
  return ec ? 0 : size;
}

absl::StatusOr<PointCloud> MakeModel(const std::string& name, const std::string& shared) {
  if (name == "teapot-scan-164") {
    absl::StatusOr<PointCloud> full = ReadPointCloud(shared + "/data/clouds/teapot-scan.ply");
    if (!full.ok()) return full.status();
    return SubsampleForGridSide(*full, 0, 164);
  }
  const std::string file = shared + "/data/clouds/" + name + ".ply";
  if (FileSize(file) > 0) return ReadPointCloud(file);
  int millions = 0;
  if (name.rfind("torus-", 0) == 0 && name.back() == 'M' &&
      absl::SimpleAtoi(name.substr(6, name.size() - 7), &millions) && millions > 0) {
    SynthOptions s;
    s.shape = "torus";
    s.points = int64_t{millions} * 1'000'000;
    s.seed = 1;
    return SynthesizeShape(s);
  }
  return absl::InvalidArgumentError(absl::StrCat("unknown model ", name));
}

uint64_t Checksum(const VoxelGrid& grid) {
  uint64_t h = 1469598103934665603ull;
  for (int64_t i = 0; i < grid.size(); ++i) {
    h ^= static_cast<uint8_t>(grid.at(i));
    h *= 1099511628211ull;
  }
  return h;
}

int Run(int argc, char** argv) {
  std::string model = "teapot-scan-164", cache = "/tmp", shared = MEMBRANE_SOURCE_DIR "/../shared";
  int repeat = 5;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--model") model = next();
    else if (a == "--repeat") repeat = std::stoi(next());
    else if (a == "--cache") cache = next();
    else if (a == "--shared") shared = next();
    else {
      std::fprintf(stderr,
                   "usage: bench_separation [--model teapot-scan-164|torus-NM|CLOUD] [--repeat R] "
                   "[--cache DIR] [--shared DIR]\n");
      return 2;
    }
  }
  absl::StatusOr<PointCloud> cloud = MakeModel(model, shared);
  if (!cloud.ok()) {
    std::fprintf(stderr, "%s\n", cloud.status().ToString().c_str());
    return 1;
  }
  absl::StatusOr<Voxelization> vox = Voxelize(cloud->points, VoxelizeOptions{});
  if (!vox.ok()) {
    std::fprintf(stderr, "%s\n", vox.status().ToString().c_str());
    return 1;
  }
  VoxelGrid& grid = vox->grid;
  const std::string cached = absl::StrCat(cache, "/bench_separation-", model, ".states");
  const bool big = grid.size() > (int64_t{1} << 27);
  if (big && FileSize(cached) ==
                 static_cast<uintmax_t>(grid.size())) {
    std::ifstream in(cached, std::ios::binary);
    in.read(reinterpret_cast<char*>(grid.mutable_states().data()), grid.size());
  } else {
    ShrinkOptions o;
    o.separation.enabled = false;
    o.holes.enabled = false;
    o.refill.enabled = false;
    o.connect_inside_hard = false;
    absl::StatusOr<ShrinkResult> r =
        ShrinkMembrane(grid, cloud->points, o, {}, CancelToken::Never());
    if (!r.ok()) {
      std::fprintf(stderr, "%s\n", r.status().ToString().c_str());
      return 1;
    }
    if (big) {
      std::ofstream out(cached, std::ios::binary);
      out.write(reinterpret_cast<const char*>(grid.states().data()), grid.size());
    }
  }
  const HardVoxelPoints points(grid, cloud->points);
  std::printf("bench_separation %s: grid %dx%dx%d, %zu points, load average %s\n", model.c_str(),
              grid.dim(0), grid.dim(1), grid.dim(2), cloud->points.size(),
              LoadAverage().c_str());
  std::vector<double> cpus;
  uint64_t sum = 0;
  bool same = true;
  for (int r = 0; r < repeat; ++r) {
    VoxelGrid copy = grid;
    const double c0 = ClockSeconds(CLOCK_THREAD_CPUTIME_ID);
    absl::StatusOr<PieceSeparationStats> s =
        SeparateDataPieces(copy, PieceSeparationOptions{}, CancelToken::Never(), &points);
    const double c1 = ClockSeconds(CLOCK_THREAD_CPUTIME_ID);
    if (!s.ok()) {
      std::fprintf(stderr, "%s\n", s.status().ToString().c_str());
      return 1;
    }
    cpus.push_back(c1 - c0);
    const uint64_t h = Checksum(copy);
    if (r > 0 && h != sum) same = false;
    sum = h;
    std::printf("run %d: %.4f CPU s (%.4f wall), %d pieces, %s, cut %lld, fraction %.4f\n", r,
                c1 - c0, s->seconds, s->pieces, s->separated ? "separated" : "not separated",
                static_cast<long long>(s->cut_voxels), s->cut_fraction);
  }
  std::printf("median %.4f CPU s over %d; states checksum %016llx%s; load average %s\n",
              Median(cpus), repeat, static_cast<unsigned long long>(sum),
              same ? "" : " DIFFERS BETWEEN RUNS", LoadAverage().c_str());
  return 0;
}

}  // namespace
}  // namespace membrane

int main(int argc, char** argv) { return membrane::Run(argc, argv); }

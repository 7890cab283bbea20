// bench_shrink: time of the membrane shrink (ShrinkMembrane only) at the formula-(1) voxel
// size, on --threads threads (default one), per model, with per-generation rows like the
// paper's Tables 1 to 4, peak RSS, topology, and Open3D Poisson on the same real clouds side
// by side. See README.md.
//
// Each model runs in a forked child so that its peak RSS (getrusage) is its own and a crash
// or an error in one model does not hide the others.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"
#include "core/engine/membrane_invariants.h"
#include "core/engine/membrane_shrinker.h"
#include "core/engine/voxel_topology.h"
#include "core/engine/voxelization.h"
#include "core/io/point_cloud_io.h"
#include "core/synth/shape_catalog.h"
#include "core/synth/synthesize.h"
#include "tests/bench/bench_clouds.h"
#include "tests/bench/bench_util.h"
#include "tests/bench/open3d_peer.h"

namespace membrane::bench {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// Options

struct BenchOptions {
  bool quick = false;
  int repeat = 3;
  bool repeat_given = false;
  std::vector<std::string> models;  // filter; empty = all
  std::string shared_dir;
  bool open3d = true;
  Open3dPeer peer;
  ShrinkOptions shrink;  // default, or the handle retry's sizes of --retry
};

constexpr char kUsage[] =
    "usage: bench_shrink [--quick] [--models a,b,c,d|NAME,...] [--repeat R] [--shared DIR]\n"
    "                    [--python PATH] [--open3d-threads N] [--open3d-timeout S]\n"
    "                    [--no-open3d] [--retry T,S,W] [--threads N] [--voxelwise-ratio R]\n"
    "                    [--coarse-plates V,P]\n"
    "  --quick           small sizes only, R=1, no open3d (the ctest smoke)\n"
    "  --models LIST     a|real, b|scaling, c|million, d|tall, e|small, f|big (4M and 10M\n"
    "                    points, only when named), or any part of a\n"
    "                    model name\n"
    "  --repeat R        shrink repetitions per model, the median is reported (default 3)\n"
    "  --shared DIR      the shared folder holding data/clouds (default: $MEMBRANE_SHARED_DIR,\n"
    "                    else <repo>/../shared)\n"
    "  --python PATH     interpreter with open3d (default /usr/bin/python3)\n"
    "  --open3d-threads  threads for Open3D (default 1, like the one-core shrink)\n"
    "  --open3d-timeout  stop Open3D after S seconds per cloud (default 0: never)\n"
    "  --no-open3d       skip the Open3D Poisson peer\n"
    "  --retry T,S,W     the handle retry's tunnel, short-loop and wall-notch plate sizes\n"
    "                    (ShrinkOptions::retry; 0 = none of that kind)\n"
    "  --threads N       the shrink's threads, 1..256 (ShrinkOptions::threads; default 1;\n"
    "                    CPU seconds are the whole process's)\n"
    "  --voxelwise-ratio R  a closed form adding at most one voxel per R of the grid is\n"
    "                    applied voxel by voxel (ShrinkOptions::closed_form_voxelwise_ratio;\n"
    "                    default 256; 0 = always by planes)\n"
    "  --coarse-plates V,P  on grids of at least V voxels the plates of P and more run on the\n"
    "                    grid 4 times coarser (ShrinkOptions::coarse_plates; default 2^30,41;\n"
    "                    V = 0: never)\n";

std::optional<BenchOptions> ParseArgs(int argc, char** argv) {
  BenchOptions o;
  const char* env = std::getenv("MEMBRANE_SHARED_DIR");
  o.shared_dir = env != nullptr && *env != '\0' ? env : MEMBRANE_SOURCE_DIR "/../shared";
  o.peer.script = MEMBRANE_BENCH_DIR "/open3d_poisson.py";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::optional<std::string> {
      if (i + 1 >= argc) return std::nullopt;
      return std::string(argv[++i]);
    };
    if (arg == "--quick") {
      o.quick = true;
    } else if (arg == "--no-open3d") {
      o.open3d = false;
    } else if (arg == "--models") {
      auto v = value();
      if (!v) return std::nullopt;
      o.models = absl::StrSplit(*v, ',', absl::SkipEmpty());
    } else if (arg == "--repeat") {
      auto v = value();
      if (!v || !absl::SimpleAtoi(*v, &o.repeat) || o.repeat < 1) return std::nullopt;
      o.repeat_given = true;
    } else if (arg == "--retry") {
      auto v = value();
      std::vector<std::string> f;
      if (v) f = absl::StrSplit(*v, ',');
      if (f.size() != 3 || !absl::SimpleAtoi(f[0], &o.shrink.retry.tunnel_min_plate) ||
          !absl::SimpleAtoi(f[1], &o.shrink.retry.short_loop_min_plate) ||
          !absl::SimpleAtoi(f[2], &o.shrink.retry.wall_notch_min_plate)) {
        return std::nullopt;
      }
    } else if (arg == "--threads") {
      auto v = value();
      if (!v || !absl::SimpleAtoi(*v, &o.shrink.threads) || o.shrink.threads < 1 ||
          o.shrink.threads > 256) {
        return std::nullopt;
      }
    } else if (arg == "--voxelwise-ratio") {
      auto v = value();
      if (!v || !absl::SimpleAtoi(*v, &o.shrink.closed_form_voxelwise_ratio) ||
          o.shrink.closed_form_voxelwise_ratio < 0) {
        return std::nullopt;
      }
    } else if (arg == "--coarse-plates") {
      auto v = value();
      std::vector<std::string> f;
      if (v) f = absl::StrSplit(*v, ',');
      if (f.size() != 2 || !absl::SimpleAtoi(f[0], &o.shrink.coarse_plates.min_voxels) ||
          !absl::SimpleAtoi(f[1], &o.shrink.coarse_plates.min_plate) ||
          !ValidateShrinkOptions(o.shrink).ok()) {
        return std::nullopt;
      }
    } else if (arg == "--shared") {
      auto v = value();
      if (!v) return std::nullopt;
      o.shared_dir = *v;
    } else if (std::optional<bool> peer_flag = ParseOpen3dFlag(arg, value, o.peer)) {
      if (!*peer_flag) return std::nullopt;
    } else {
      return std::nullopt;
    }
  }
  if (o.quick) {
    if (!o.repeat_given) o.repeat = 1;
    o.open3d = false;
  }
  return o;
}

// ---------------------------------------------------------------------------------------------
// Models

struct Model {
  std::string name;
  char letter;        // a real, b scaling, c million, d tall, e small (teapot class)
  std::string group;  // real, scaling, million, tall
  std::string how;    // one line: where the cloud comes from
  std::string file;   // real clouds: the .ply, also given to Open3D
  std::function<absl::StatusOr<PointCloud>()> make;
  ShapeTopology expected;       // shells and sorted genus a correct reconstruction has
  bool genus_asserted = true;   // false for the teapot (data/README.md)
  bool named_only = false;      // run only when --models names it (minutes and gigabytes)
};

// The expected reconstruction of the shared clouds (../shared/data/README.md).
void SetExpectedForRealCloud(Model& m) {
  m.expected = {1, {m.name.rfind("rocker-arm", 0) == 0 ? 1 : 0}};
  m.genus_asserted = m.name.rfind("teapot", 0) != 0;
}

std::string Describe(const ShapeTopology& t, bool genus_asserted = true) {
  return absl::StrCat(t.shells, t.shells == 1 ? " shell" : " shells", ", genus ",
                      genus_asserted ? absl::StrCat("[", absl::StrJoin(t.genus, ","), "]")
                                     : std::string("not asserted"));
}

bool Selected(const BenchOptions& o, const Model& m) {
  if (o.models.empty()) return !m.named_only;
  for (const std::string& t : o.models) {
    if (t.size() == 1) {  // a letter, never a substring
      if (t[0] == m.letter) return true;
      continue;
    }
    if (t == m.group || m.name.find(t) != std::string::npos) return true;
  }
  return false;
}

Model ScalingModel(const std::string& shape, int side) {
  Model m;
  m.name = absl::StrCat(shape, "-", side);
  m.letter = 'b';
  m.group = "scaling";
  m.how = absl::StrCat("synthetic ", shape, ", N = 6 D^2 points for a ~", side, "^3 grid");
  m.make = [shape, side] { return SynthForGridSide(shape, side); };
  m.expected = ExpectedTopology(shape);
  return m;
}

// Every model, in run order, and the lines to print for what was skipped.
std::vector<Model> AllModels(const BenchOptions& o, std::vector<std::string>& notes) {
  std::vector<Model> models;
  // (a) real clouds
  const fs::path clouds = fs::path(o.shared_dir) / "data" / "clouds";
  std::error_code ec;
  if (!fs::is_directory(clouds, ec)) {
    notes.push_back(absl::StrCat("(a) real clouds: SKIPPED, ", clouds.string(),
                                 " is absent (set MEMBRANE_SHARED_DIR or --shared)"));
  } else {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(clouds, ec)) {
      if (e.path().extension() == ".ply") files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    if (o.quick) {  // one real cloud: the first 100k variable-density one
      auto it = std::find_if(files.begin(), files.end(), [](const fs::path& p) {
        return p.stem().string().find("variable") != std::string::npos;
      });
      files = it == files.end() ? std::vector<fs::path>{} : std::vector<fs::path>{*it};
    }
    if (files.empty()) notes.push_back(absl::StrCat("(a) real clouds: none in ", clouds.string()));
    for (const fs::path& f : files) {
      Model m;
      m.name = f.stem().string();
      m.letter = 'a';
      m.group = "real";
      m.file = f.string();
      m.how = absl::StrCat("real cloud ", f.string());
      m.make = [file = m.file] { return ReadPointCloud(file); };
      SetExpectedForRealCloud(m);
      models.push_back(std::move(m));
    }
  }
  // (e) the paper's teapot grid class (164x104x82, 1.4 M voxels): the teapot scan subsampled
  // so that formula (1) gives 164 voxels along its long axis (x), 164x83x104 with padding.
  if (!o.quick && fs::is_regular_file(clouds / "teapot-scan.ply", ec)) {
    Model m;
    m.name = "teapot-scan-164";
    m.letter = 'e';
    m.group = "small";
    m.how = absl::StrCat("real cloud ", (clouds / "teapot-scan.ply").string(),
                         ", every k-th point for a formula-(1) grid 164 voxels long (the "
                         "paper's teapot grid class)");
    m.make = [file = (clouds / "teapot-scan.ply").string()]() -> absl::StatusOr<PointCloud> {
      absl::StatusOr<PointCloud> full = ReadPointCloud(file);
      if (!full.ok()) return full.status();
      return SubsampleForGridSide(*full, 0, 164);
    };
    SetExpectedForRealCloud(m);
    models.push_back(std::move(m));
  } else if (!o.quick) {
    notes.push_back("(e) teapot-scan-164: SKIPPED, no teapot-scan.ply in the clouds folder");
  }
  // (b) scaling: the two spheres at ~100^3, 200^3, 400^3 (quick: 50^3 and 100^3)
  const std::vector<int> sides = o.quick ? std::vector<int>{50, 100} : std::vector<int>{100, 200, 400};
  for (int side : sides) models.push_back(ScalingModel(std::string(kShapeTwoSpheres), side));
  // (c) one million points: the torus (genus 1; the two spheres at 0.96 M are in (b))
  if (!o.quick) {
    Model m;
    m.name = "torus-1M";
    m.letter = 'c';
    m.group = "million";
    m.how = "synthetic torus (R 0.7, r 0.45, axis (1,1,1)), 1,000,000 points";
    m.make = [] {
      SynthOptions s;
      s.shape = std::string(kShapeTorus);
      s.points = 1'000'000;
      s.seed = 1;
      return SynthesizeShape(s);
    };
    m.expected = ExpectedTopology(std::string(kShapeTorus));
    models.push_back(std::move(m));
  }
  // (f) issue-21 scale, only when named: the same torus at 4 and 10 million points (grids of
  // 821^3 and 1295^3 voxels; the 10M one needs about 5 GB).
  if (!o.quick) {
    for (int millions : {4, 10}) {
      Model m;
      m.name = absl::StrCat("torus-", millions, "M");
      m.letter = 'f';
      m.group = "big";
      m.named_only = true;
      m.how = absl::StrCat("synthetic torus (R 0.7, r 0.45, axis (1,1,1)), ", millions,
                           ",000,000 points");
      m.make = [millions] {
        SynthOptions s;
        s.shape = std::string(kShapeTorus);
        s.points = millions * 1'000'000;
        s.seed = 1;
        return SynthesizeShape(s);
      };
      m.expected = ExpectedTopology(std::string(kShapeTorus));
      models.push_back(std::move(m));
    }
  }
  // (d) the Buddha class: three stacked unit spheres, y height 745 voxels (quick: 120)
  {
    const int height = o.quick ? 120 : 745;
    Model m;
    m.name = o.quick ? "tall-stack-120" : "tall-stack-745";
    m.letter = 'd';
    m.group = "tall";
    m.how = absl::StrCat(
        "3 unit spheres stacked along y, centres 1.43 apart (box 2 x 4.86 x 2), union surface "
        "sampled uniformly, N for a grid ",
        height, " voxels high");
    m.make = [height] { return StackedSpheresForHeight(height); };
    m.expected = {1, {0}};
    models.push_back(std::move(m));
  }
  return models;
}

// ---------------------------------------------------------------------------------------------
// Measuring one model (in the child)

struct Summary {
  std::string name;
  char letter = '?';
  bool ok = false;
  std::string error;
  int dims[3] = {0, 0, 0};
  int64_t voxels = 0;
  int64_t points = 0;
  double wall = 0.0;  // median shrink seconds
  double cpu = 0.0;
  int64_t rss_kb = 0;
  std::string topology;  // "1 / [0]", with a trailing "!" when not the expected one
  bool invariants_ok = false;
  double o3d_wall = -1.0;  // -1: not run
  double o3d_cpu = -1.0;

  std::string Serialize() const {
    return absl::StrCat(name, "\t", std::string(1, letter), "\t", ok ? 1 : 0, "\t", dims[0], "\t",
                        dims[1], "\t", dims[2], "\t", voxels, "\t", points, "\t",
                        absl::StrFormat("%.6f\t%.6f", wall, cpu), "\t", rss_kb, "\t", topology,
                        "\t", invariants_ok ? 1 : 0, "\t",
                        absl::StrFormat("%.4f\t%.4f", o3d_wall, o3d_cpu), "\t", error);
  }
  static std::optional<Summary> Parse(const std::string& line) {
    std::vector<std::string> f = absl::StrSplit(line, '\t');
    if (f.size() < 16) return std::nullopt;
    Summary s;
    s.name = f[0];
    s.letter = f[1].empty() ? '?' : f[1][0];
    s.ok = f[2] == "1";
    bool good = absl::SimpleAtoi(f[3], &s.dims[0]) && absl::SimpleAtoi(f[4], &s.dims[1]) &&
                absl::SimpleAtoi(f[5], &s.dims[2]) && absl::SimpleAtoi(f[6], &s.voxels) &&
                absl::SimpleAtoi(f[7], &s.points) && absl::SimpleAtod(f[8], &s.wall) &&
                absl::SimpleAtod(f[9], &s.cpu) && absl::SimpleAtoi(f[10], &s.rss_kb) &&
                absl::SimpleAtod(f[13], &s.o3d_wall) && absl::SimpleAtod(f[14], &s.o3d_cpu);
    if (!good) return std::nullopt;
    s.topology = f[11];
    s.invariants_ok = f[12] == "1";
    s.error = f[15];
    return s;
  }
};

std::string Thousands(int64_t v) {
  std::string digits = absl::StrCat(v < 0 ? -v : v);
  std::string out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return v < 0 ? "-" + out : out;
}

int64_t PeakRssKb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

// What the handle retry did, for the shrink line.
std::string RetrySummary(const HandleRetry& r) {
  if (r.from_generation == 0) return "no generation below its plate size";
  if (r.loose_tunnels == 0) return "not needed";
  if (!r.ran) return absl::StrFormat("%d loose tunnels, no handles", r.loose_tunnels);
  const std::string rim =
      r.web_voxels > 0 ? absl::StrFormat(", web rim %.0f%% hard", 100 * r.web_hard_rim) : "";
  return absl::StrFormat("%d loose tunnels%s, genus %d -> %d from generation %d, %s",
                         r.loose_tunnels, rim, r.genus_before,
                         r.kept ? r.genus_after : r.genus_before, r.from_generation,
                         r.kept ? "kept" : "not kept");
}

bool SameCounters(const ShrinkResult& a, const ShrinkResult& b) {
  if (a.generations.size() != b.generations.size()) return false;
  for (size_t i = 0; i < a.generations.size(); ++i) {
    const GenerationStats& x = a.generations[i];
    const GenerationStats& y = b.generations[i];
    if (x.plate_size != y.plate_size || x.soft_voxels != y.soft_voxels ||
        x.started_contractions != y.started_contractions || x.backtrackings != y.backtrackings ||
        x.contractions != y.contractions) {
      return false;
    }
  }
  return true;
}

Summary RunModel(const BenchOptions& o, const Model& m, bool open3d_available,
                 const std::string& open3d_version) {
  Summary s;
  s.name = m.name;
  s.letter = m.letter;
  std::printf("\n== (%c) %s: %s\n", m.letter, m.name.c_str(), m.how.c_str());
  auto fail = [&](const absl::Status& status, const char* what) {
    s.error = absl::StrCat(what, ": ", status.ToString());
    std::printf("ERROR %s\n", s.error.c_str());
    return s;
  };

  const double t_load = Now();
  absl::StatusOr<PointCloud> cloud = m.make();
  if (!cloud.ok()) return fail(cloud.status(), m.file.empty() ? "synthesize" : "read");
  const double load_seconds = Now() - t_load;
  s.points = static_cast<int64_t>(cloud->points.size());
  absl::StatusOr<Box3d> bounds = CheckedBounds(cloud->points);
  if (!bounds.ok()) return fail(bounds.status(), "bounds");
  const double voxel_size = EstimateVoxelSize(*bounds, s.points);

  std::vector<double> walls, cpus, voxelize_seconds;
  std::vector<ShrinkResult> results;
  std::optional<Voxelization> vox;
  int64_t hard = 0;
  for (int r = 0; r < o.repeat; ++r) {
    vox.reset();  // one grid alive at a time
    const double tv = Now();
    absl::StatusOr<Voxelization> v = Voxelize(cloud->points, VoxelizeOptions{});  // formula (1)
    if (!v.ok()) return fail(v.status(), "voxelize");
    voxelize_seconds.push_back(Now() - tv);
    vox = std::move(*v);
    hard = vox->hard_voxels;
    const double w0 = Now();
    const double c0 = ClockSeconds(CLOCK_PROCESS_CPUTIME_ID);
    absl::StatusOr<ShrinkResult> result =
        ShrinkMembrane(vox->grid, cloud->points, o.shrink, {}, CancelToken::Never());
    const double c1 = ClockSeconds(CLOCK_PROCESS_CPUTIME_ID);
    const double w1 = Now();
    if (!result.ok()) return fail(result.status(), "shrink");
    walls.push_back(w1 - w0);
    cpus.push_back(c1 - c0);
    results.push_back(std::move(*result));
  }
  s.rss_kb = PeakRssKb();
  const auto& d = vox->grid.dims();
  s.dims[0] = d[0];
  s.dims[1] = d[1];
  s.dims[2] = d[2];
  s.voxels = vox->grid.size();
  s.wall = Median(walls);
  s.cpu = Median(cpus);
  // The run whose wall time is closest to the median gives the per-generation rows.
  size_t mid = 0;
  for (size_t i = 1; i < walls.size(); ++i) {
    if (std::abs(walls[i] - s.wall) < std::abs(walls[mid] - s.wall)) mid = i;
  }
  const ShrinkResult& res = results[mid];
  bool deterministic = true;
  for (const ShrinkResult& r : results) deterministic = deterministic && SameCounters(r, res);

  std::printf("grid %dx%dx%d with padding (%s voxels), voxel %.6g, points %s, hard voxels %s\n",
              d[0], d[1], d[2], Thousands(s.voxels).c_str(), voxel_size,
              Thousands(s.points).c_str(), Thousands(hard).c_str());
  std::printf("%4s %5s %5s %12s %10s %11s %13s %12s %7s %6s %6s %9s\n", "gen", "plate",
              "level", "soft voxels", "started", "backtracks", "contractions", "undone",
              "passes", "local", "rounds", "seconds");
  double generation_sum = 0.0;
  for (const GenerationStats& g : res.generations) {
    std::printf("%4d %5d %5d %12s %10s %11s %13s %12s %7d %6d %6d %9.3f\n", g.generation,
                g.plate_size, g.level, Thousands(g.soft_voxels).c_str(),
                Thousands(g.started_contractions).c_str(), Thousands(g.backtrackings).c_str(),
                Thousands(g.contractions).c_str(), Thousands(g.undone_contractions).c_str(),
                g.passes, g.local_passes, g.closed_form_rounds, g.seconds);
    generation_sum += g.seconds;
  }
  if (res.coarse_plates.generations > 0) {
    std::printf("coarse plates: generations 1-%d on the grid %d times coarser, %s voxels "
                "lifted, %.3f s with the coarse grid and the lift\n",
                res.coarse_plates.generations, res.coarse_plates.factor,
                Thousands(res.coarse_plates.lifted_voxels).c_str(), res.coarse_plates.seconds);
  }
  std::printf("shrink: median %.3f s wall, %.3f s CPU over R=%d (wall runs %s); %.1f ns/voxel "
              "wall, %.1f CPU; generations %.3f s + rest (post-process, handle retry %.3f s: %s) "
              "%.3f s%s\n",
              s.wall, s.cpu, o.repeat,
              absl::StrJoin(walls, " ", [](std::string* out, double w) {
                absl::StrAppend(out, absl::StrFormat("%.3f", w));
              }).c_str(),
              1e9 * s.wall / s.voxels, 1e9 * s.cpu / s.voxels, generation_sum,
              res.handle_retry.seconds, RetrySummary(res.handle_retry).c_str(),
              res.seconds - generation_sum,
              deterministic ? "" : "; COUNTERS DIFFER BETWEEN RUNS");
  // The steps after the generations, each over R (wall: they run on the calling thread).
  auto step_walls = [&](auto seconds_of) {
    return absl::StrJoin(results, " ", [&](std::string* out, const ShrinkResult& r) {
      absl::StrAppend(out, absl::StrFormat("%.3f", seconds_of(r)));
    });
  };
  std::printf("after the generations (s, each run): piece separation %s (%d pieces, %s); "
              "hole opening %s\n",
              step_walls([](const ShrinkResult& r) { return r.separation.seconds; }).c_str(),
              res.separation.pieces, res.separation.separated ? "separated" : "not separated",
              step_walls([](const ShrinkResult& r) { return r.holes.seconds; }).c_str());
  std::printf("%s %.2f s, voxelize %.3f s (median, not in the shrink time); peak RSS %.1f MB\n",
              m.file.empty() ? "synthesize" : "read", load_seconds, Median(voxelize_seconds),
              s.rss_kb / 1024.0);

  // Untimed checks on the last run's final DMS.
  const VoxelTopology topo = ComputeVoxelTopology(vox->grid);
  InvariantOptions io;
  io.expected_hard_voxels = hard;
  const absl::Status inv = CheckMembraneInvariants(vox->grid, io);
  s.invariants_ok = inv.ok();
  std::vector<int> genus = topo.genus;
  std::sort(genus.begin(), genus.end());
  const bool expected = topo.shells == m.expected.shells &&
                        (!m.genus_asserted || genus == m.expected.genus) && topo.cavities == 0;
  s.topology = absl::StrCat(topo.shells, " / [", absl::StrJoin(topo.genus, ","), "]",
                            expected ? "" : "!");
  std::printf("topology: %d %s, genus [%s], cavities %d, inside hard %s -> %s after "
              "post-process; invariants %s; expected %s: %s\n",
              topo.shells, topo.shells == 1 ? "shell" : "shells",
              absl::StrJoin(topo.genus, ",").c_str(), topo.cavities,
              Thousands(res.post_process.inside_hard_before).c_str(),
              Thousands(res.post_process.inside_hard_after).c_str(),
              inv.ok() ? "OK" : inv.ToString().c_str(),
              Describe(m.expected, m.genus_asserted).c_str(), expected ? "OK" : "MISMATCH");
  vox.reset();
  cloud->points.clear();
  cloud->points.shrink_to_fit();
  s.ok = inv.ok();
  if (!inv.ok()) s.error = "invariants violated";

  if (!m.file.empty()) {
    if (!o.open3d) {
      std::printf("open3d: not run (--no-open3d or --quick)\n");
    } else if (!open3d_available) {
      std::printf("open3d not available (%s)\n", open3d_version.c_str());
    } else {
      std::fflush(stdout);
      absl::StatusOr<Open3dRun> peer = RunOpen3dPoisson(o.peer, m.file);
      if (absl::IsDeadlineExceeded(peer.status())) {
        std::printf("open3d: %s; ratio open3d / membrane > %.0fx wall\n",
                    std::string(peer.status().message()).c_str(),
                    o.peer.timeout_seconds / s.wall);
      } else if (!peer.ok()) {
        std::printf("open3d: FAILED: %s\n", peer.status().ToString().c_str());
      } else {
        s.o3d_wall = peer->seconds;
        s.o3d_cpu = peer->cpu_seconds;
        std::printf("open3d %s poisson depth 9, %d thread(s): normals %.2f + orient %.2f + "
                    "poisson %.2f = %.2f s wall (process CPU %.2f s incl. reading), %s faces, "
                    "peak RSS %.0f MB\n",
                    open3d_version.c_str(), o.peer.threads, peer->normals_seconds,
                    peer->orient_seconds, peer->poisson_seconds, peer->seconds,
                    peer->cpu_seconds, Thousands(peer->faces).c_str(),
                    peer->peak_rss_kb / 1024.0);
        std::printf("open3d json: %s\n", peer->json.c_str());
        std::printf("ratio open3d_seconds / membrane_shrink_seconds: %.0fx wall (%.0fx CPU)\n",
                    s.o3d_wall / s.wall, s.o3d_cpu / s.cpu);
      }
    }
  }
  return s;
}

// Runs `m` in a forked child; its summary comes back through a pipe.
Summary RunModelInChild(const BenchOptions& o, const Model& m, bool open3d_available,
                        const std::string& open3d_version) {
  std::fflush(stdout);
  std::fflush(stderr);
  int fds[2];
  Summary failed;
  failed.name = m.name;
  failed.letter = m.letter;
  if (pipe(fds) != 0) {
    failed.error = "pipe failed";
    return failed;
  }
  const pid_t pid = fork();
  if (pid < 0) {
    failed.error = "fork failed";
    return failed;
  }
  if (pid == 0) {
    close(fds[0]);
    const std::string line = RunModel(o, m, open3d_available, open3d_version).Serialize() + "\n";
    std::fflush(stdout);
    const ssize_t written = write(fds[1], line.data(), line.size());
    close(fds[1]);
    _exit(written == static_cast<ssize_t>(line.size()) ? 0 : 3);
  }
  close(fds[1]);
  std::string line;
  char buffer[4096];
  ssize_t n;
  while ((n = read(fds[0], buffer, sizeof buffer)) > 0) line.append(buffer, static_cast<size_t>(n));
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (WIFSIGNALED(status)) {
    failed.error = absl::StrCat("child killed by signal ", WTERMSIG(status));
    std::printf("ERROR %s: %s\n", m.name.c_str(), failed.error.c_str());
    return failed;
  }
  while (!line.empty() && line.back() == '\n') line.pop_back();
  std::optional<Summary> s = Summary::Parse(line);
  if (!s) {
    failed.error = "no summary from the child";
    return failed;
  }
  return *s;
}

// ---------------------------------------------------------------------------------------------
// Report

std::string CpuModel() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) {
      const size_t colon = line.find(':');
      return colon == std::string::npos ? line : line.substr(colon + 2);
    }
  }
  return "unknown CPU";
}

const Summary* Find(const std::vector<Summary>& all, const std::string& name) {
  for (const Summary& s : all) {
    if (s.name == name && s.ok) return &s;
  }
  return nullptr;
}

const char* Verdict(bool met) { return met ? "MET" : "NOT MET"; }

void PrintSummary(const std::vector<Summary>& all, bool quick, int threads) {
  std::printf("\n== summary: shrink only, median of R, %d thread(s) (ns/voxel over the padded grid)\n",
              threads);
  std::printf("(shells/g: shells / genus per shell, \"!\" = not the expected topology)\n");
  std::printf("%-23s %13s %6s %9s %7s %7s %6s %6s %6s %-11s %8s %6s\n", "model", "grid",
              "Mvox", "points", "wall s", "CPU s", "ns/v w", "ns/v c", "RSS MB", "shells/g",
              "open3d s", "ratio");
  for (const Summary& s : all) {
    if (!s.ok && s.voxels == 0) {
      std::printf("%-23s ERROR %s\n", s.name.c_str(), s.error.c_str());
      continue;
    }
    const std::string grid = absl::StrCat(s.dims[0], "x", s.dims[1], "x", s.dims[2]);
    std::string o3d = "-", ratio = "-";
    if (s.o3d_wall >= 0) {
      o3d = absl::StrFormat("%.1f", s.o3d_wall);
      ratio = absl::StrFormat("%.0fx", s.o3d_wall / s.wall);
    }
    std::printf("%-23s %13s %6.1f %9s %7.3f %7.3f %6.0f %6.0f %6.0f %-11s %8s %6s%s\n",
                s.name.c_str(), grid.c_str(), s.voxels / 1e6, Thousands(s.points).c_str(), s.wall,
                s.cpu, 1e9 * s.wall / s.voxels, 1e9 * s.cpu / s.voxels, s.rss_kb / 1024.0,
                s.topology.c_str(), o3d.c_str(),
                ratio.c_str(), s.ok ? "" : "  (invariants violated)");
  }

  std::printf("\n== targets (verdict on CPU seconds of the shrink; wall shown too)%s\n",
              quick ? ": --quick sizes, only the small-grid target applies" : "");
  // The teapot's 164x104x82 class itself: the subsampled teapot scan.
  for (const Summary& s : all) {
    if (s.letter == 'e' && s.ok) {
      std::printf("164x104x82-class grid under 0.1 s: %s %dx%dx%d: %.3f s wall, %.3f s CPU: %s\n",
                  s.name.c_str(), s.dims[0], s.dims[1], s.dims[2], s.wall, s.cpu,
                  Verdict(s.cpu < 0.1));
    }
  }
  // The real clouds at full density (2-4 M voxels, 1.5-3x the class).
  int met_wall = 0, met_cpu = 0, real = 0;
  double worst = 0.0;
  for (const Summary& s : all) {
    if (s.letter != 'a' || !s.ok) continue;
    ++real;
    met_wall += s.wall < 0.1;
    met_cpu += s.cpu < 0.1;
    worst = std::max(worst, s.wall);
  }
  if (real > 0) {
    std::printf("  real clouds at full density (2-4 M voxels) under 0.1 s: %d/%d wall, %d/%d "
                "CPU (slowest %.3f s wall): %s\n",
                met_wall, real, met_cpu, real, worst, Verdict(met_cpu == real));
  } else {
    std::printf("  real clouds at full density: none was run\n");
  }
  for (const Summary& s : all) {
    if (s.name == "two-spheres-100" && s.ok) {
      std::printf("  %s (%dx%dx%d): %.3f s wall, %.3f s CPU: %s\n", s.name.c_str(), s.dims[0],
                  s.dims[1], s.dims[2], s.wall, s.cpu, Verdict(s.cpu < 0.1));
    }
  }
  for (const Summary& s : all) {
    if (s.name == "tall-stack-745" && s.ok) {
      std::printf("309x745x309-class under 10 s and < 1 GB: %s %dx%dx%d: %.2f s wall, %.2f s "
                  "CPU, %.0f MB: %s\n",
                  s.name.c_str(), s.dims[0], s.dims[1], s.dims[2], s.wall, s.cpu,
                  s.rss_kb / 1024.0, Verdict(s.cpu < 10.0 && s.rss_kb < 1024 * 1024));
    }
  }
  for (const Summary& s : all) {
    if ((s.letter == 'c' || (s.letter == 'b' && s.points >= 900'000)) && s.ok) {
      std::printf("1M points under 15 s: %s (%s points): %.2f s wall, %.2f s CPU: %s\n",
                  s.name.c_str(), Thousands(s.points).c_str(), s.wall, s.cpu,
                  Verdict(s.cpu < 15.0));
    }
  }
  const Summary* small = Find(all, "two-spheres-100");
  const Summary* big = Find(all, "two-spheres-400");
  if (small != nullptr && big != nullptr) {
    const double a_w = small->wall / small->voxels, b_w = big->wall / big->voxels;
    const double a_c = small->cpu / small->voxels, b_c = big->cpu / big->voxels;
    std::printf("time/voxel growth 100^3 -> 400^3 < 2x: %.1f -> %.1f ns wall (%.2fx), %.1f -> "
                "%.1f ns CPU (%.2fx): %s\n",
                1e9 * a_w, 1e9 * b_w, b_w / a_w, 1e9 * a_c, 1e9 * b_c, b_c / a_c,
                Verdict(b_c / a_c < 2.0));
  }
}

int Main(int argc, char** argv) {
  std::optional<BenchOptions> parsed = ParseArgs(argc, argv);
  if (!parsed) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  const BenchOptions& o = *parsed;
  std::vector<std::string> notes;
  std::vector<Model> models = AllModels(o, notes);

  bool open3d_available = false;
  std::string open3d_version = "not checked";
  if (o.open3d) {
    absl::StatusOr<std::string> v = Open3dVersion(o.peer);
    open3d_available = v.ok();
    open3d_version = v.ok() ? *v : std::string(v.status().message());
  }
  const std::time_t now = std::time(nullptr);
  char date[64];
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M:%S", std::localtime(&now));
  std::printf("bench_shrink%s: %s, %s, %ld online CPUs, load average %s\n",
              o.quick ? " --quick" : "", date, CpuModel().c_str(), sysconf(_SC_NPROCESSORS_ONLN),
              LoadAverage().c_str());
  std::printf("shrink only (ShrinkMembrane, default ShrinkOptions), one thread, formula-(1) "
              "voxel size, median of R=%d; shared dir %s\n",
              o.repeat, o.shared_dir.c_str());
  if (!o.open3d) {
    std::printf("open3d: not run%s\n", o.quick ? " (--quick)" : " (--no-open3d)");
  } else if (open3d_available) {
    std::printf("open3d %s via %s, %d thread(s), run once per real cloud\n",
                open3d_version.c_str(), o.peer.python.c_str(), o.peer.threads);
  } else {
    std::printf("open3d not available: %s\n", open3d_version.c_str());
  }
  for (const std::string& n : notes) std::printf("%s\n", n.c_str());

  std::vector<Summary> all;
  for (const Model& m : models) {
    if (!Selected(o, m)) continue;
    all.push_back(RunModelInChild(o, m, open3d_available, open3d_version));
  }
  PrintSummary(all, o.quick, o.shrink.threads);
  std::printf("load average at the end: %s\n", LoadAverage().c_str());
  bool ok = true;
  for (const Summary& s : all) ok = ok && s.ok;
  return ok ? 0 : 1;
}

}  // namespace
}  // namespace membrane::bench

int main(int argc, char** argv) { return membrane::bench::Main(argc, argv); }

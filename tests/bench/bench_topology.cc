// bench_topology: the topology table of the shrink. Every cloud of ../shared/data/clouds at
// 1x, 1.25x, 1.5x and 2x its formula-(1) voxel size, and the synthetic shapes of
// tests/engine/shrink_topology_test.cc, each shrunk once (ShrinkMembrane, default options): the
// shells and genus against the expected ones, the shrink's wall seconds, and for every miss
// where its handles and merges are, what the handle retry did and how many plugged holes were
// opened. See README.md.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <string>
#include <vector>

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
#include "core/synth/cube_pinholes.h"
#include "core/synth/shape_catalog.h"
#include "core/synth/synthesize.h"
#include "tests/bench/bench_util.h"
#include "tests/support/shared_models.h"
#include "tests/support/topology_locator.h"

namespace membrane::bench {
namespace {

constexpr char kUsage[] =
    "usage: bench_topology [--factors 1,1.25,1.5,2] [--models NAME,...] [--no-synthetic]\n"
    "                      [--no-real] [--locate] [--retry T,S,W] [--thick-wall-run K]\n"
    "                      [--thick-wall-detour R] [--thin-part-spread S] [--depth-bound D]\n"
    "                      [--rerun-thin K] [--no-retry] [--strict-only] [--no-close-cut-loops]\n"
    "                      [--no-hole-opening] [--far-steps F] [--near-far-steps N]\n"
    "                      [--max-cut-fraction C]\n"
    "                      [--shared DIR]\n"
    "  --factors LIST   multiples of the formula-(1) voxel size (default 1,1.25,1.5,2)\n"
    "  --models LIST    only clouds and shapes whose name contains one of these\n"
    "  --locate         print where the handles and merges of every miss are\n"
    "  --retry T,S,W    the handle retry's tunnel, short-loop and wall-notch plate sizes\n"
    "                   (ShrinkOptions::retry; 0 = none of that kind)\n"
    "  --thick-wall-run K  the thick-wall incursion test's longest hard run (1 = the\n"
    "                   paper's test only; ChainRules::thick_wall_run)\n"
    "  --thick-wall-detour R  the radius within which the thick-wall run's ends joined through\n"
    "                   the outside stop the test (0 = off; ChainRules::thick_wall_detour)\n"
    "  --thin-part-spread S  and the run's points must lie S voxels off their best plane\n"
    "                   (0 = not read; ChainRules::thin_part_min_spread)\n"
    "  --depth-bound D  the small plates' depth bound (0 = unbounded; ChainRules::depth_bound)\n"
    "  --rerun-thin K   when a result has handles, shrink the grid again with a thick-wall run\n"
    "                   of K and keep that result if it has fewer handles and no fewer shells\n"
    "                   (a candidate rule measured here; its time is added to the row's)\n"
    "  --far-steps F, --near-far-steps N  the piece separation's far webs: non-hard voxels\n"
    "                   more than F steps from the data, then N (0 = no third trial)\n"
    "  --max-cut-fraction C  the piece separation's size test (PieceSeparationOptions)\n"
    "  --no-hole-opening  leave plugged holes closed (ShrinkOptions::holes.enabled false)\n"
    "  --no-retry       no handle retry (ShrinkOptions::retry.enabled false)\n"
    "  --strict-only    every generation under the handle retry's strict guard sizes, no retry\n"
    "  --no-close-cut-loops  the piece separation returns only simple cut voxels\n"
    "                   (PieceSeparationOptions::close_cut_loops false)\n"
    "  --shared DIR     the shared folder holding data/clouds (default: $MEMBRANE_SHARED_DIR,\n"
    "                   else <repo>/../shared)\n";

struct Options {
  std::vector<double> factors = {1.0, 1.25, 1.5, 2.0};
  std::vector<std::string> models;
  bool synthetic = true;
  bool real = true;
  bool locate = false;
  int rerun_thin = 0;  // 0: no rerun
  std::string shared_dir;
  ShrinkOptions shrink;
};

bool ParseArgs(int argc, char** argv, Options& o) {
  const char* env = std::getenv("MEMBRANE_SHARED_DIR");
  o.shared_dir = env != nullptr && *env != '\0' ? env : MEMBRANE_SOURCE_DIR "/../shared";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--factors" && has_value) {
      o.factors.clear();
      for (absl::string_view f : absl::StrSplit(argv[++i], ',', absl::SkipEmpty())) {
        double v = 0;
        if (!absl::SimpleAtod(f, &v) || v <= 0) return false;
        o.factors.push_back(v);
      }
    } else if (arg == "--models" && has_value) {
      o.models = absl::StrSplit(argv[++i], ',', absl::SkipEmpty());
    } else if (arg == "--shared" && has_value) {
      o.shared_dir = argv[++i];
    } else if (arg == "--retry" && has_value) {
      std::vector<std::string> f = absl::StrSplit(argv[++i], ',');
      if (f.size() != 3 || !absl::SimpleAtoi(f[0], &o.shrink.retry.tunnel_min_plate) ||
          !absl::SimpleAtoi(f[1], &o.shrink.retry.short_loop_min_plate) ||
          !absl::SimpleAtoi(f[2], &o.shrink.retry.wall_notch_min_plate)) {
        return false;
      }
    } else if (arg == "--thick-wall-run" && has_value) {
      if (!absl::SimpleAtoi(argv[++i], &o.shrink.chain.thick_wall_run)) return false;
    } else if (arg == "--thick-wall-detour" && has_value) {
      if (!absl::SimpleAtoi(argv[++i], &o.shrink.chain.thick_wall_detour)) return false;
    } else if (arg == "--thin-part-spread" && has_value) {
      if (!absl::SimpleAtod(argv[++i], &o.shrink.chain.thin_part_min_spread)) return false;
    } else if (arg == "--depth-bound" && has_value) {
      if (!absl::SimpleAtoi(argv[++i], &o.shrink.chain.depth_bound)) return false;
    } else if (arg == "--rerun-thin" && has_value) {
      if (!absl::SimpleAtoi(argv[++i], &o.rerun_thin)) return false;
    } else if (arg == "--far-steps" && has_value) {
      if (!absl::SimpleAtoi(argv[++i], &o.shrink.separation.far_steps)) return false;
    } else if (arg == "--near-far-steps" && has_value) {
      if (!absl::SimpleAtoi(argv[++i], &o.shrink.separation.near_far_steps)) return false;
    } else if (arg == "--max-cut-fraction" && has_value) {
      if (!absl::SimpleAtod(argv[++i], &o.shrink.separation.max_cut_fraction)) return false;
    } else if (arg == "--strict-only") {
      o.shrink.guard = StrictGuardSizes(o.shrink);
      o.shrink.retry.enabled = false;
    } else if (arg == "--no-close-cut-loops") {
      o.shrink.separation.close_cut_loops = false;
    } else if (arg == "--no-retry") {
      o.shrink.retry.enabled = false;
    } else if (arg == "--no-separation") {
      o.shrink.separation.enabled = false;
    } else if (arg == "--no-hole-opening") {
      o.shrink.holes.enabled = false;
    } else if (arg == "--no-synthetic") {
      o.synthetic = false;
    } else if (arg == "--no-real") {
      o.real = false;
    } else if (arg == "--locate") {
      o.locate = true;
    } else {
      return false;
    }
  }
  return !o.factors.empty();
}

bool Selected(const Options& o, const std::string& name) {
  if (o.models.empty()) return true;
  for (const std::string& m : o.models)
    if (name.find(m) != std::string::npos) return true;
  return false;
}

struct Tally {
  int right = 0, runs = 0;
  double seconds = 0;
  double hole_seconds = 0;  // of which the opening of plugged holes
};

// What the handle retry did, when it ran.
std::string RetryNote(const HandleRetry& r) {
  if (!r.ran) return "";
  return absl::StrFormat("  retry: genus %d, %s%s", r.genus_before,
                         r.kept ? absl::StrCat("kept, genus ", r.genus_after) : "not kept",
                         r.web_voxels > 0
                             ? absl::StrFormat(" (web %d voxels, rim %.0f%% hard)", r.web_voxels,
                                               100 * r.web_hard_rim)
                             : "");
}

// Shrinks `cloud` at `voxel_size` and prints one row; true when the topology is `expected`.
bool RunOne(const Options& o, const std::string& name, double factor, const PointCloud& cloud,
            double voxel_size, const ShapeTopology& expected, bool genus_asserted, Tally& tally) {
  VoxelizeOptions vo;
  vo.voxel_size = voxel_size;
  absl::StatusOr<Voxelization> vox = Voxelize(cloud.points, vo);
  std::string row = absl::StrFormat("%-26s %5.2fx ", name, factor);
  if (!vox.ok()) {
    std::printf("%sERROR voxelize: %s\n", row.c_str(), vox.status().ToString().c_str());
    ++tally.runs;
    return false;
  }
  const VoxelGrid voxelized = o.rerun_thin > 0 ? vox->grid : VoxelGrid();
  double t0 = Now();
  absl::StatusOr<ShrinkResult> result =
      ShrinkMembrane(vox->grid, cloud.points, o.shrink, {}, CancelToken::Never());
  double seconds = Now() - t0;
  ++tally.runs;
  if (!result.ok()) {
    std::printf("%sERROR shrink: %s\n", row.c_str(), result.status().ToString().c_str());
    return false;
  }
  VoxelTopology topo = ComputeVoxelTopology(vox->grid);
  std::string rerun_note;
  auto handles = [](const VoxelTopology& t) {
    return std::accumulate(t.genus.begin(), t.genus.end(), 0);
  };
  // --rerun-thin: the candidate rule of tests/bench/2026-12-02-separations.txt, whose cost
  // (a second shrink of every result with a handle) is what decides it, so it is timed too.
  if (o.rerun_thin > 0 && handles(topo) > 0) {
    VoxelGrid again = voxelized;
    ShrinkOptions thin = o.shrink;
    thin.chain.thick_wall_run = o.rerun_thin;
    t0 = Now();
    absl::StatusOr<ShrinkResult> second = ShrinkMembrane(again, cloud.points, thin, {}, CancelToken::Never());
    if (second.ok()) {
      VoxelTopology topo2 = ComputeVoxelTopology(again);
      seconds += Now() - t0;
      const bool keep = handles(topo2) < handles(topo) && topo2.shells >= topo.shells;
      rerun_note = absl::StrFormat("  rerun: genus %d, %s", handles(topo2),
                                   keep ? "kept" : "not kept");
      if (keep) {
        vox->grid = std::move(again);
        topo = std::move(topo2);
        result = std::move(second);
      }
    }
  }
  tally.seconds += seconds;
  tally.hole_seconds += result->holes.seconds;
  InvariantOptions io;
  io.expected_hard_voxels = vox->hard_voxels;
  const absl::Status inv = CheckMembraneInvariants(vox->grid, io);
  std::vector<int> genus = topo.genus;
  std::sort(genus.begin(), genus.end());
  const bool right = inv.ok() && topo.shells == expected.shells && topo.cavities == 0 &&
                     (!genus_asserted || genus == expected.genus);
  tally.right += right;
  const auto& d = vox->grid.dims();
  std::string holes_note =
      result->holes.opened > 0 ? absl::StrCat("  holes opened: ", result->holes.opened) : "";
  const PieceSeparationStats& sep = result->separation;
  if (sep.pieces > 1) {
    const std::string cut =
        absl::StrFormat("cut %d + web %d voxels (far webs from %d steps), %d loops closed",
                        sep.cut_voxels, sep.web_voxels, sep.far_steps_cut, sep.loops_closed);
    absl::StrAppend(&holes_note, absl::StrFormat("  pieces %d, %s", sep.pieces,
                                                 sep.separated ? cut : "not cut"));
    if (sep.shells_after > 0)
      absl::StrAppend(&holes_note,
                      absl::StrFormat(" (%d/%d -> %d/%d, cavities %d, cut/piece %.3f, %.3f s)",
                                      sep.shells_before, sep.genus_before, sep.shells_after,
                                      sep.genus_after, sep.cavities_after, sep.cut_fraction,
                                      sep.seconds));
  }
  std::printf("%s%12s %7.3f  %-16s %-16s %s%s%s%s%s\n", row.c_str(),
              absl::StrCat(d[0], "x", d[1], "x", d[2]).c_str(), seconds,
              absl::StrCat(topo.shells, " / [", absl::StrJoin(genus, ","), "]").c_str(),
              genus_asserted ? absl::StrCat(expected.shells, " / [",
                                            absl::StrJoin(expected.genus, ","), "]")
                                   .c_str()
                             : absl::StrCat(expected.shells, " / -").c_str(),
              right ? "ok" : "MISS", inv.ok() ? "" : absl::StrCat(" ", inv.ToString()).c_str(),
              RetryNote(result->handle_retry).c_str(), holes_note.c_str(), rerun_note.c_str());
  if (!right && o.locate) {
    std::printf("%s", testing::LocateHandlesAndContacts(vox->grid).c_str());
  }
  std::fflush(stdout);
  return right;
}

void PrintHeader() {
  std::printf("%-26s %6s %12s %7s  %-16s %-16s %s\n", "cloud", "voxel", "grid", "shrink",
              "shells / genus", "expected", "");
}

void RunReal(const Options& o, Tally& tally) {
  for (const testing::SharedModel& m : testing::SharedModels()) {
    for (const std::string& kind : m.kinds) {
      const std::string name = absl::StrCat(m.model, "-", kind);
      if (!Selected(o, name)) continue;
      const std::string path = absl::StrCat(o.shared_dir, "/data/clouds/", name, ".ply");
      absl::StatusOr<PointCloud> cloud = ReadPointCloud(path);
      if (!cloud.ok()) {
        std::printf("%-26s SKIPPED: %s\n", name.c_str(), cloud.status().ToString().c_str());
        continue;
      }
      absl::StatusOr<Box3d> box = CheckedBounds(cloud->points);
      if (!box.ok()) continue;
      const double l = EstimateVoxelSize(*box, static_cast<int64_t>(cloud->points.size()));
      for (double f : o.factors) {
        RunOne(o, name, f, *cloud, f * l, m.expected, m.genus_asserted, tally);
      }
    }
  }
}

// The runs of tests/engine/shrink_topology_test.cc.
void RunSynthetic(const Options& o, Tally& tally) {
  for (const char* shape : {"sphere", "two-spheres", "torus", "capped-sphere"}) {
    for (double density : {1.0, 30.0}) {
      const std::string name = absl::StrCat(shape, density > 1 ? "-density30" : "");
      if (!Selected(o, name)) continue;
      SynthOptions s;
      s.shape = shape;
      s.points = 60000;
      s.density_ratio = density;
      s.seed = 7;
      absl::StatusOr<PointCloud> cloud = SynthesizeShape(s);
      if (!cloud.ok()) continue;
      absl::StatusOr<Box3d> box = CheckedBounds(cloud->points);
      if (!box.ok()) continue;
      const double l = EstimateVoxelSize(*box, static_cast<int64_t>(cloud->points.size()));
      for (double f : o.factors) {
        RunOne(o, name, f, *cloud, f * l, ExpectedTopology(shape), true, tally);
      }
    }
  }
  if (!Selected(o, "cube-pinholes")) return;
  SynthOptions s;
  s.shape = "cube-pinholes";
  s.points = 60000;
  absl::StatusOr<CubePinholesGrid> grid = CubePinholesGridFor(s);
  absl::StatusOr<PointCloud> cloud = SynthesizeCubePinholes(s);
  if (!grid.ok() || !cloud.ok()) return;
  for (double f : o.factors) {
    RunOne(o, "cube-pinholes", f, *cloud, f * grid->voxel_size, ExpectedTopology("cube-pinholes"),
           true, tally);
  }
}

int Main(int argc, char** argv) {
  Options o;
  if (!ParseArgs(argc, argv, o)) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  std::printf("bench_topology: load average %s; shrink wall seconds, one run each\n",
              LoadAverage().c_str());
  PrintHeader();
  Tally real, synthetic;
  if (o.real) RunReal(o, real);
  if (o.synthetic) RunSynthetic(o, synthetic);
  std::printf("right: real %d of %d (shrink %.2f s, hole opening %.3f s), synthetic %d of %d "
              "(shrink %.2f s, hole opening %.3f s); load average %s\n",
              real.right, real.runs, real.seconds, real.hole_seconds, synthetic.right,
              synthetic.runs, synthetic.seconds, synthetic.hole_seconds, LoadAverage().c_str());
  return 0;
}

}  // namespace
}  // namespace membrane::bench

int main(int argc, char** argv) { return membrane::bench::Main(argc, argv); }

// bench_topology: the topology table of the shrink. Every cloud of ../shared/data/clouds at
// 1x, 1.25x, 1.5x and 2x its formula-(1) voxel size, and the synthetic shapes of
// tests/engine/shrink_topology_test.cc and cup_topology_test.cc, each shrunk once
// (ShrinkMembrane, default options): the shells and genus against the expected ones (for the
// cups, the inside open too), the shrink's wall seconds, and for every miss
// where its handles and merges are, what the handle retry did and how many plugged holes were
// opened. On request, the data's own topology beside the membrane's (--data-genus, --probe)
// and the same runs on an even sample of each reference mesh (--reference). See README.md.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <random>
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
#include "core/io/mesh_io.h"
#include "core/io/point_cloud_io.h"
#include "core/synth/cube_pinholes.h"
#include "core/synth/shape_catalog.h"
#include "core/synth/synthesize.h"
#include "tests/bench/bench_util.h"
#include "tests/support/cup_cloud.h"
#include "tests/support/shared_models.h"
#include "tests/support/topology_locator.h"

namespace membrane::bench {
namespace {

constexpr char kUsage[] =
    "usage: bench_topology [--factors 1,1.25,1.5,2] [--models NAME,...] [--no-synthetic]\n"
    "                      [--no-real] [--locate] [--genus-per-generation] [--retry T,S,W]\n"
    "                      [--thick-wall-run K]\n"
    "                      [--thick-wall-detour R] [--thin-part-spread S]\n"
    "                      [--thin-wall-face-gap G] [--depth-bound D]\n"
    "                      [--rerun-thin K] [--no-retry] [--strict-only] [--no-close-cut-loops]\n"
    "                      [--no-hole-opening] [--wall-core-depth D] [--wall-faces-spread S]\n"
    "                      [--far-steps F]\n"
    "                      [--near-far-steps N]\n"
    "                      [--max-cut-fraction C] [--all-cut-counts] [--split-reach R]\n"
    "                      [--data-genus R]\n"
    "                      [--probe X,Y,Z,R] [--reference N] [--slices X,Y,Z,R]\n"
    "                      [--pocket-rays K] [--pocket-depth D] [--pocket-loops L]\n"
    "                      [--clearance-samples K] [--passage-sectors P] [--threads N]\n"
    "                      [--shared DIR]\n"
    "  --factors LIST   multiples of the formula-(1) voxel size (default 1,1.25,1.5,2)\n"
    "  --models LIST    only clouds and shapes whose name contains one of these\n"
    "  --locate         print where the handles and merges of every miss are\n"
    "  --genus-per-generation  print the solid's shells and genus after every generation\n"
    "  --retry T,S,W    the handle retry's tunnel, short-loop and wall-notch plate sizes\n"
    "                   (ShrinkOptions::retry; 0 = none of that kind)\n"
    "  --thick-wall-run K  the thick-wall incursion test's longest hard run (1 = the\n"
    "                   paper's test only; ChainRules::thick_wall_run)\n"
    "  --thick-wall-detour R  the radius within which the thick-wall run's ends joined through\n"
    "                   the outside stop the test (0 = off; ChainRules::thick_wall_detour)\n"
    "  --thin-part-spread S  and the run's points must lie S voxels off their best plane\n"
    "                   (0 = not read; ChainRules::thin_part_min_spread)\n"
    "  --thin-wall-face-gap G  a run whose ends face surfaces G voxels apart is a thin part\n"
    "                   whatever the detour (0 = not read; ChainRules::thin_wall_face_gap)\n"
    "  --depth-bound D  the small plates' depth bound (0 = unbounded; ChainRules::depth_bound)\n"
    "  --rerun-thin K   when a result has handles, shrink the grid again with a thick-wall run\n"
    "                   of K and keep that result if it has fewer handles and no fewer shells\n"
    "                   (a candidate rule measured here; its time is added to the row's)\n"
    "  --far-steps F, --near-far-steps N  the piece separation's far webs: non-hard voxels\n"
    "                   more than F steps from the data, then N (0 = no third trial)\n"
    "  --max-cut-fraction C  the piece separation's size test (PieceSeparationOptions)\n"
    "  --all-cut-counts  the size test counts every cut voxel, not only those between the\n"
    "                   two pieces' data (PieceSeparationOptions::between_only false)\n"
    "  --split-reach R  the piece separation's split of touching hard voxels by their points\n"
    "                   (0 = not split; PieceSeparationOptions::split_reach)\n"
    "  --data-genus R   also print the topology of the data itself: the hard voxels grown by R\n"
    "                   26-neighbour steps, cavities filled (0..2), the whole data and each\n"
    "                   piece of data alone (with --locate, their loops)\n"
    "  --probe X,Y,Z,R  with --data-genus: the topology once the membrane is made the grown\n"
    "                   data inside the box of half-width R around voxel (X, Y, Z)\n"
    "  --reference N    also run N points spread evenly over data/models/MODEL.obj (where\n"
    "                   present) at each size of the model's first cloud's voxel: the\n"
    "                   object without the scan's gaps\n"
    "  --pocket-rays K, --pocket-depth D, --pocket-loops L  the gap refill's pockets: rays\n"
    "                   backed by a data wall (0 = no pockets), the wall's depth, the loops it\n"
    "                   may close (GapRefillOptions::pocket_backed_rays, pocket_wall_depth,\n"
    "                   max_pocket_loops)\n"
    "  --slices X,Y,Z,R print the final states in the box of half-width R around voxel\n"
    "                   (X, Y, Z), one z layer at a time, outside voxels as their generation\n"
    "                   labels; with data/models/MODEL.obj, those carved out of the model\n"
    "                   marked, a count per label, and the topology with them put back\n"
    "  --no-hole-opening  leave plugged holes closed (ShrinkOptions::holes.enabled false)\n"
    "  --wall-core-depth D  the hole opening's wall-core test: a plug is no hole when every\n"
    "                   ray across it meeting data has the outside within D voxels past it\n"
    "                   (0 = not tested; HoleOpeningOptions::wall_core_depth)\n"
    "  --wall-faces-spread S  nor when the points around every hard voxel those rays meet\n"
    "                   lie S voxels or more off their best plane: a thin wall's two faces\n"
    "                   (0 = not tested; HoleOpeningOptions::wall_faces_spread)\n"
    "  --clearance-samples K, --passage-sectors P  the hole opening's clearance spots per\n"
    "                   axis and the sectors of a passage lined with data (9: no passage\n"
    "                   test; HoleOpeningOptions)\n"
    "  --no-retry       no handle retry (ShrinkOptions::retry.enabled false)\n"
    "  --strict-only    every generation under the handle retry's strict guard sizes, no retry\n"
    "  --no-close-cut-loops  the piece separation returns only simple cut voxels\n"
    "                   (PieceSeparationOptions::close_cut_loops false)\n"
    "  --threads N      the shrink's threads, 1..256 (ShrinkOptions::threads; default 1):\n"
    "                   the same membrane on any count, sooner on the 1e9-voxel grids\n"
    "  --shared DIR     the shared folder holding data/clouds (default: $MEMBRANE_SHARED_DIR,\n"
    "                   else <repo>/../shared)\n";

struct Options {
  std::vector<double> factors = {1.0, 1.25, 1.5, 2.0};
  std::vector<std::string> models;
  bool synthetic = true;
  bool real = true;
  bool locate = false;
  bool genus_per_generation = false;  // the solid's topology after every generation
  int rerun_thin = 0;  // 0: no rerun
  int data_genus = -1;  // -1: not printed; else the hard voxels' growth in steps
  int reference_points = 0;  // > 0: also run a dense sample of each model's reference mesh
  std::vector<std::array<int, 4>> probes;  // x, y, z, r boxes read against the grown data
  std::vector<std::array<int, 4>> slices;  // x, y, z, r boxes whose states are printed
  std::string shared_dir;
  ShrinkOptions shrink;
};

// "X,Y,Z,R" (--probe, --slices) appended to `boxes`; false when it is not four integers.
bool ParseBox(const char* text, std::vector<std::array<int, 4>>& boxes) {
  const std::vector<std::string> f = absl::StrSplit(text, ',');
  std::array<int, 4> box{};
  if (f.size() != 4) return false;
  for (int k = 0; k < 4; ++k)
    if (!absl::SimpleAtoi(f[k], &box[k])) return false;
  boxes.push_back(box);
  return true;
}

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
    } else if (arg == "--threads" && has_value) {
      if (!absl::SimpleAtoi(argv[++i], &o.shrink.threads) || o.shrink.threads < 1 ||
          o.shrink.threads > 256) {
        return false;
      }
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
    } else if (arg == "--thin-wall-face-gap" && has_value) {
      if (!absl::SimpleAtod(argv[++i], &o.shrink.chain.thin_wall_face_gap)) return false;
    } else if (arg == "--thin-wall-face-min-plate" && has_value) {
      if (!absl::SimpleAtoi(argv[++i], &o.shrink.chain.thin_wall_face_min_plate)) return false;
    } else if (arg == "--thin-wall-face-max-run" && has_value) {
      if (!absl::SimpleAtoi(argv[++i], &o.shrink.chain.thin_wall_face_max_run)) return false;
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
    } else if (arg == "--all-cut-counts") {
      o.shrink.separation.between_only = false;
    } else if (arg == "--split-reach" && has_value) {
      if (!absl::SimpleAtod(argv[++i], &o.shrink.separation.split_reach)) return false;
    } else if (arg == "--data-genus" && has_value) {
      if (!absl::SimpleAtoi(argv[++i], &o.data_genus) || o.data_genus < 0 ||
          o.data_genus > VoxelGrid::kPadding) {
        return false;
      }
    } else if (arg == "--probe" && has_value) {
      if (!ParseBox(argv[++i], o.probes)) return false;
    } else if (arg == "--pocket-rays" && has_value) {
      if (!absl::SimpleAtoi(argv[++i], &o.shrink.refill.pocket_backed_rays)) return false;
    } else if (arg == "--pocket-loops" && has_value) {
      if (!absl::SimpleAtoi(argv[++i], &o.shrink.refill.max_pocket_loops)) return false;
    } else if (arg == "--pocket-depth" && has_value) {
      if (!absl::SimpleAtoi(argv[++i], &o.shrink.refill.pocket_wall_depth)) return false;
    } else if (arg == "--slices" && has_value) {
      if (!ParseBox(argv[++i], o.slices)) return false;
    } else if (arg == "--reference" && has_value) {
      if (!absl::SimpleAtoi(argv[++i], &o.reference_points) || o.reference_points < 0)
        return false;
    } else if (arg == "--clearance-samples" && has_value) {
      if (!absl::SimpleAtoi(argv[++i], &o.shrink.holes.clearance_samples)) return false;
    } else if (arg == "--passage-sectors" && has_value) {
      if (!absl::SimpleAtoi(argv[++i], &o.shrink.holes.passage_sectors)) return false;
    } else if (arg == "--strict-only") {
      o.shrink.guard = StrictGuardSizes(o.shrink, o.shrink.guard);
      o.shrink.retry.enabled = false;
    } else if (arg == "--no-close-cut-loops") {
      o.shrink.separation.close_cut_loops = false;
    } else if (arg == "--no-retry") {
      o.shrink.retry.enabled = false;
    } else if (arg == "--no-separation") {
      o.shrink.separation.enabled = false;
    } else if (arg == "--wall-core-depth" && has_value) {
      if (!absl::SimpleAtoi(argv[++i], &o.shrink.holes.wall_core_depth)) return false;
    } else if (arg == "--wall-faces-spread" && has_value) {
      if (!absl::SimpleAtod(argv[++i], &o.shrink.holes.wall_faces_spread)) return false;
    } else if (arg == "--no-hole-opening") {
      o.shrink.holes.enabled = false;
    } else if (arg == "--no-synthetic") {
      o.synthetic = false;
    } else if (arg == "--no-real") {
      o.real = false;
    } else if (arg == "--locate") {
      o.locate = true;
    } else if (arg == "--genus-per-generation") {
      o.genus_per_generation = true;
    } else {
      return false;
    }
  }
  return !o.factors.empty() && (o.probes.empty() || o.data_genus >= 0);
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

// The hard voxels of `voxelized` (a grid straight from Voxelize) as a 0/1 mask, and their
// 26-components holding at least 1% of them (the piece separation's pieces of data), largest
// first, each as a mask of its own.
std::vector<uint8_t> HardMask(const VoxelGrid& voxelized) {
  std::vector<uint8_t> hard(voxelized.size(), 0);
  for (int64_t i = 0; i < voxelized.size(); ++i) hard[i] = IsHard(voxelized.at(i));
  return hard;
}

std::vector<std::vector<uint8_t>> HardPieces(const VoxelGrid& voxelized) {
  const std::vector<uint8_t> hard = HardMask(voxelized);
  const int64_t total = std::accumulate(hard.begin(), hard.end(), int64_t{0});
  std::vector<int32_t> label(voxelized.size(), -1);
  std::vector<std::vector<int64_t>> components;
  for (int64_t i = 0; i < voxelized.size(); ++i) {
    if (hard[i] == 0 || label[i] >= 0) continue;
    const int32_t id = static_cast<int32_t>(components.size());
    std::vector<int64_t> members = {i};
    label[i] = id;
    for (size_t k = 0; k < members.size(); ++k) {
      for (int64_t o : voxelized.neighbour_offsets()) {
        const int64_t w = members[k] + o;  // hard voxels are never on the array border
        if (hard[w] != 0 && label[w] < 0) {
          label[w] = id;
          members.push_back(w);
        }
      }
    }
    components.push_back(std::move(members));
  }
  std::sort(components.begin(), components.end(),
            [](const auto& a, const auto& b) { return a.size() > b.size(); });
  std::vector<std::vector<uint8_t>> pieces;
  for (const std::vector<int64_t>& c : components) {
    if (static_cast<int64_t>(c.size()) * 100 < total) break;
    std::vector<uint8_t> mask(voxelized.size(), 0);
    for (int64_t v : c) mask[v] = 1;
    pieces.push_back(std::move(mask));
  }
  return pieces;
}

// The outside of the solid `solid` (0/1 per voxel of `like`): the 6-connected non-solid
// voxels reached from the array border (which must not be solid). What it leaves is the solid
// with its cavities filled.
std::vector<uint8_t> OutsideOf(const VoxelGrid& like, const std::vector<uint8_t>& solid) {
  const auto& d = like.dims();
  const std::array<int64_t, 3> st = like.strides();
  std::vector<uint8_t> outside(like.size(), 0);
  std::vector<int64_t> queue;
  for (int64_t i = 0; i < like.size(); ++i) {
    if (like.OnArrayBorder(like.CoordOf(i))) {
      outside[i] = 1;
      queue.push_back(i);
    }
  }
  while (!queue.empty()) {
    const int64_t v = queue.back();
    queue.pop_back();
    const Coord c = like.CoordOf(v);
    const int at[3] = {c.x, c.y, c.z};
    for (int axis = 0; axis < 3; ++axis) {
      for (int sign : {-1, 1}) {
        const int to = at[axis] + sign;
        if (to < 0 || to >= d[axis]) continue;
        const int64_t w = v + sign * st[axis];
        if (outside[w] != 0 || solid[w] != 0) continue;
        outside[w] = 1;
        queue.push_back(w);
      }
    }
  }
  return outside;
}

// The solid of the data itself: the voxels of `grown` (hard voxels) and every voxel within
// `radius` 26-neighbour steps of one (never the array border), with the regions the
// 6-connected outside cannot reach from the border filled, as the reference's r-tube check
// fills them: the solid a membrane would be if it were exactly the grown data. Hard voxels
// stay hard (the locator's contacts read them), the rest is soft; BOUNDARY where a face
// neighbour is outside (the locator's thinning peels from there).
VoxelGrid GrownDataSolid(const VoxelGrid& voxelized, std::vector<uint8_t> grown, int radius) {
  const auto& d = voxelized.dims();
  const std::array<int64_t, 3> st = voxelized.strides();
  const std::vector<uint8_t> seed = grown;
  // A 26-neighbour step is one step along each axis in turn.
  for (int step = 0; step < radius; ++step) {
    for (int axis = 0; axis < 3; ++axis) {
      std::vector<uint8_t> next = grown;
      for (int64_t i = 0; i < voxelized.size(); ++i) {
        if (grown[i] == 0) continue;
        const Coord c = voxelized.CoordOf(i);
        const int at = axis == 0 ? c.x : axis == 1 ? c.y : c.z;
        if (at > 1) next[i - st[axis]] = 1;
        if (at < d[axis] - 2) next[i + st[axis]] = 1;
      }
      grown = std::move(next);
    }
  }
  const std::vector<uint8_t> outside = OutsideOf(voxelized, grown);
  VoxelGrid solid(d, voxelized.origin(), voxelized.voxel_size(), OutsideState(0));
  for (int64_t i = 0; i < voxelized.size(); ++i) {
    if (outside[i] != 0) continue;
    bool boundary = false;
    for (int axis = 0; axis < 3; ++axis)
      boundary |= outside[i - st[axis]] != 0 || outside[i + st[axis]] != 0;
    solid.set(i, seed[i] != 0 ? (boundary ? kBoundaryHard : kInsideHard)
                              : (boundary ? kBoundarySoft : kInsideSoft));
  }
  return solid;
}

// A grid whose solid is `solid` (0/1 per voxel of `like`), every solid voxel inside soft.
VoxelGrid SolidGrid(const VoxelGrid& like, const std::vector<uint8_t>& solid) {
  VoxelGrid g(like.dims(), like.origin(), like.voxel_size(), OutsideState(0));
  for (int64_t i = 0; i < like.size(); ++i)
    if (solid[i] != 0) g.set(i, kInsideSoft);
  return g;
}

// "S / [g,...] (v,...)": shells, and each shell's genus and voxels, the largest shell first.
std::string ShellsBySize(const VoxelTopology& t) {
  std::vector<int> order(t.shells);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return t.voxels[a] > t.voxels[b]; });
  std::vector<int> genus;
  std::vector<int64_t> voxels;
  for (int k : order) {
    genus.push_back(t.genus[k]);
    voxels.push_back(t.voxels[k]);
  }
  return absl::StrCat(t.shells, " / [", absl::StrJoin(genus, ","), "] (",
                      absl::StrJoin(voxels, ","), " voxels)");
}

// The voxels of row (y, z) whose centre lies inside `mesh` (a closed model): crossings of the
// row's line with the faces' yz projections, counted by parity. All zero without a mesh.
std::vector<uint8_t> InsideModelRow(const TriangleMesh* mesh, const VoxelGrid& grid, int y,
                                    int z) {
  const auto& d = grid.dims();
  std::vector<uint8_t> inside(d[0], 0);
  if (mesh == nullptr) return inside;
  const std::array<double, 3> c = grid.Center({0, y, z});
  std::vector<double> xs;
  for (const auto& f : mesh->faces) {
    const Point3f& a = mesh->vertices[f[0]];
    const Point3f& b = mesh->vertices[f[1]];
    const Point3f& e = mesh->vertices[f[2]];
    // Barycentric coordinates of (c[1], c[2]) in the face's yz projection.
    const double det = (b[1] - a[1]) * (e[2] - a[2]) - (e[1] - a[1]) * (b[2] - a[2]);
    if (det == 0) continue;
    const double u = ((c[1] - a[1]) * (e[2] - a[2]) - (e[1] - a[1]) * (c[2] - a[2])) / det;
    const double v = ((b[1] - a[1]) * (c[2] - a[2]) - (c[1] - a[1]) * (b[2] - a[2])) / det;
    if (u < 0 || v < 0 || u + v > 1) continue;
    xs.push_back(a[0] + u * (b[0] - a[0]) + v * (e[0] - a[0]));
  }
  std::sort(xs.begin(), xs.end());
  for (int x = 0; x < d[0]; ++x) {
    const double cx = grid.Center({x, y, z})[0];
    inside[x] = (std::lower_bound(xs.begin(), xs.end(), cx) - xs.begin()) % 2;
  }
  return inside;
}

// The box of half-width b[3] around voxel (b[0], b[1], b[2]), clipped to the grid less
// `margin` layers: lo and hi per axis.
struct Box {
  std::array<int, 3> lo, hi;
};
Box ClippedBox(const VoxelGrid& grid, const std::array<int, 4>& b, int margin) {
  Box box;
  for (int k = 0; k < 3; ++k) {
    box.lo[k] = std::max(b[k] - b[3], margin);
    box.hi[k] = std::min(b[k] + b[3], grid.dim(k) - 1 - margin);
  }
  return box;
}

// --slices with the model: per generation label (and its plate size), in the box, the outside
// voxels whose centre lies inside the model (carved out of the object), and the outside
// voxels with a hard face neighbour outside the model and inside it (the data walls' outer
// faces, reached from the outside, and their inner faces, reached from a carved pocket).
// Then the topology of the membrane with every voxel of the box carved inside the model put
// back (label 0, the piece separation's cut, left out; cavities filled): what any refill of
// the pockets carved into the objects there could reach at best.
void PrintCarvedByLabel(const VoxelGrid& grid, const std::array<int, 4>& b,
                        const TriangleMesh& mesh, const std::vector<GenerationStats>& generations) {
  std::array<int64_t, kMaxGenerationLabel + 1> carved{}, outer{}, inner{};
  const auto st = grid.strides();
  const Box box = ClippedBox(grid, b, 1);
  std::vector<uint8_t> solid(grid.size(), 0);
  for (int64_t i = 0; i < grid.size(); ++i) solid[i] = !IsOutside(grid.at(i));
  int64_t put_back = 0;
  for (int z = box.lo[2]; z <= box.hi[2]; ++z)
    for (int y = box.lo[1]; y <= box.hi[1]; ++y) {
      const std::vector<uint8_t> in_model = InsideModelRow(&mesh, grid, y, z);
      for (int x = box.lo[0]; x <= box.hi[0]; ++x) {
        const int64_t v = grid.Index(x, y, z);
        if (!IsOutside(grid.at(v))) continue;
        const int g = GenerationLabel(grid.at(v));
        bool beside_hard = false;
        for (int k = 0; k < 3; ++k)
          beside_hard |= IsHard(grid.at(v - st[k])) || IsHard(grid.at(v + st[k]));
        carved[g] += in_model[x];
        (in_model[x] != 0 ? inner : outer)[g] += beside_hard;
        if (in_model[x] != 0 && g > 0) {
          solid[v] = 1;
          ++put_back;
        }
      }
    }
  std::printf("  label (plate): carved inside the model / beside hard outside the model / "
              "beside hard inside the model\n");
  for (int g = 0; g <= kMaxGenerationLabel; ++g) {
    if (carved[g] + outer[g] + inner[g] == 0) continue;
    const int plate =
        g >= 1 && g <= static_cast<int>(generations.size()) ? generations[g - 1].plate_size : 0;
    std::printf("  %5d (%2d): %8lld %8lld %8lld\n", g, plate, static_cast<long long>(carved[g]),
                static_cast<long long>(outer[g]), static_cast<long long>(inner[g]));
  }
  const std::vector<uint8_t> out = OutsideOf(grid, solid);
  for (int64_t i = 0; i < grid.size(); ++i) solid[i] = out[i] == 0;
  std::printf("  carved voxels inside the model put back: %lld, then %s\n",
              static_cast<long long>(put_back),
              ShellsBySize(ComputeVoxelTopology(SolidGrid(grid, solid))).c_str());
}

// --slices: the final states in the box, one z layer at a time (rows y, columns x): "#" hard,
// "f" frozen, "." soft inside, "b" soft boundary, and an outside voxel's generation label
// (which generation carved it); with the model, a label whose voxel's centre lies inside the
// model is starred (boxes of half-width 20 or less: three characters a voxel) or a capital
// letter (A = 0; wider boxes: one character a voxel, labels past 25 print as 25).
void PrintSlices(const VoxelGrid& grid, const std::array<int, 4>& b, const TriangleMesh* mesh) {
  const Box box = ClippedBox(grid, b, 0);
  const bool wide = b[3] > 20;
  for (int z = box.lo[2]; z <= box.hi[2]; ++z) {
    std::printf("  z = %d, x from %d, y from %d\n", z, box.lo[0], box.lo[1]);
    for (int y = box.lo[1]; y <= box.hi[1]; ++y) {
      std::string line = absl::StrFormat("  %4d ", y);
      const std::vector<uint8_t> in_model = InsideModelRow(mesh, grid, y, z);
      for (int x = box.lo[0]; x <= box.hi[0]; ++x) {
        const VoxelState s = grid.at(grid.Index(x, y, z));
        if (!IsOutside(s)) {
          absl::StrAppend(&line, wide ? "" : "  ",
                          IsHard(s) ? "#" : IsFrozen(s) ? "f" : IsBoundary(s) ? "b" : ".");
        } else if (wide) {
          const char* digits =
              in_model[x] != 0 ? "ABCDEFGHIJKLMNOPQRSTUVWXYZ" : "0123456789abcdefghijklmnop";
          line.push_back(digits[std::min(GenerationLabel(s), 25)]);
        } else {
          absl::StrAppend(&line, absl::StrFormat(in_model[x] != 0 ? "%2d*" : "%3d",
                                                 GenerationLabel(s)));
        }
      }
      std::printf("%s\n", line.c_str());
    }
  }
}

// Shrinks `cloud` at `voxel_size` and prints one row; true when the topology is `expected`.
// `model`: the cloud's reference mesh, read for --slices, else nullptr.
bool RunOne(const Options& o, const std::string& name, double factor, const PointCloud& cloud,
            double voxel_size, const ShapeTopology& expected, bool genus_asserted, Tally& tally,
            const TriangleMesh* model = nullptr, double max_volume = 0) {
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
  // --data-genus: the data's own topology, made before the shrink changes the grid.
  VoxelGrid data_solid;
  std::string data_note;
  std::vector<VoxelGrid> piece_solids;
  if (o.data_genus >= 0) {
    data_solid = GrownDataSolid(vox->grid, HardMask(vox->grid), o.data_genus);
    data_note = absl::StrFormat("  data grown %d: %s", o.data_genus,
                                ShellsBySize(ComputeVoxelTopology(data_solid)));
    // Each piece of data alone: what the piece's own samples close, whatever its neighbours do.
    std::vector<std::string> per_piece;
    for (std::vector<uint8_t>& piece : HardPieces(vox->grid)) {
      piece_solids.push_back(GrownDataSolid(vox->grid, std::move(piece), o.data_genus));
      per_piece.push_back(ShellsBySize(ComputeVoxelTopology(piece_solids.back())));
    }
    absl::StrAppend(&data_note, "; each piece alone: ", absl::StrJoin(per_piece, "; "));
  }
  // --genus-per-generation: which generation made a handle (the count costs a pass over the
  // grid, so the row's time then includes it).
  VoxelGrid& shrinking = vox->grid;
  GenerationCallback per_generation;
  if (o.genus_per_generation) {
    per_generation = [&shrinking](const GenerationStats& g) {
      const VoxelTopology t = ComputeVoxelTopology(shrinking);
      std::printf("    generation %2d (plate %3d%s%s): %lld new outside, %lld loose tunnels, "
                  "%d shells, genus %d, cavities %d\n",
                  g.generation, g.plate_size, g.closed_form ? ", closed form" : "",
                  g.handle_retry ? ", retry" : "", static_cast<long long>(g.new_outside),
                  static_cast<long long>(g.loose_tunnels), t.shells, TotalGenus(t), t.cavities);
      std::fflush(stdout);
    };
  }
  double t0 = Now();
  absl::StatusOr<ShrinkResult> result =
      ShrinkMembrane(vox->grid, cloud.points, o.shrink, per_generation, CancelToken::Never());
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
  // The piece separation may cut hard voxels where two pieces touch; every other one stays.
  io.expected_hard_voxels = vox->hard_voxels - result->separation.hard_cut_voxels;
  const absl::Status inv = CheckMembraneInvariants(vox->grid, io);
  std::vector<int> genus = topo.genus;
  std::sort(genus.begin(), genus.end());
  // max_volume > 0 (the cups): the membrane's voxels must hold less, or the inside is filled.
  int64_t solid = 0;
  if (max_volume > 0)
    for (int64_t i = 0; i < vox->grid.size(); ++i) solid += !IsOutside(vox->grid.at(i));
  const double volume = std::pow(voxel_size, 3) * static_cast<double>(solid);
  const bool filled = max_volume > 0 && volume >= max_volume;
  const bool right = inv.ok() && topo.shells == expected.shells && topo.cavities == 0 &&
                     (!genus_asserted || genus == expected.genus) && !filled;
  tally.right += right;
  const auto& d = vox->grid.dims();
  std::string holes_note =
      result->holes.opened > 0 ? absl::StrCat("  holes opened: ", result->holes.opened) : "";
  if (result->holes.wall_cores > 0)
    absl::StrAppend(&holes_note, "  wall-core plugs kept: ", result->holes.wall_cores);
  const PieceSeparationStats& sep = result->separation;
  if (max_volume > 0) {
    absl::StrAppend(&holes_note, absl::StrFormat("  volume %.3f%s", volume,
                                                 filled ? " (inside filled)" : ""));
  }
  if (result->refill.pocket_voxels > 0) {
    absl::StrAppend(&holes_note, absl::StrFormat("  refill %d (pockets %d, loops closed %d)",
                                                 result->refill.refilled_voxels,
                                                 result->refill.pocket_voxels,
                                                 result->refill.loops_closed));
  }
  if (sep.pieces > 1) {
    std::string cut =
        absl::StrFormat("cut %d + web %d voxels (far webs from %d steps), %d loops closed",
                        sep.cut_voxels, sep.web_voxels, sep.far_steps_cut, sep.loops_closed);
    if (sep.hard_cut_voxels > 0)
      absl::StrAppend(&cut, absl::StrFormat(", %d hard cut", sep.hard_cut_voxels));
    absl::StrAppend(&holes_note, absl::StrFormat("  pieces %d, %s", sep.pieces,
                                                 sep.separated ? cut : "not cut"));
    if (sep.shells_after > 0)
      absl::StrAppend(&holes_note,
                      absl::StrFormat(" (%d/%d -> %d/%d, cavities %d, cut/piece %.3f, %.3f s)",
                                      sep.shells_before, sep.genus_before, sep.shells_after,
                                      sep.genus_after, sep.cavities_after, sep.cut_fraction,
                                      sep.seconds));
  }
  if (o.data_genus >= 0) {
    // The membrane's shells in the same form, and the voxels the membrane keeps outside the
    // grown data (webs and plugs) and the grown data's voxels it carved.
    int64_t kept_off_data = 0, carved_data = 0;
    for (int64_t i = 0; i < data_solid.size(); ++i) {
      const bool in_membrane = !IsOutside(vox->grid.at(i));
      const bool in_data = !IsOutside(data_solid.at(i));
      kept_off_data += in_membrane && !in_data;
      carved_data += in_data && !in_membrane;
    }
    absl::StrAppend(&data_note, absl::StrFormat("; membrane %s, %d voxels off the grown data, "
                                                "%d of it carved",
                                                ShellsBySize(topo), kept_off_data, carved_data));
    // --probe: inside a box around a loop, the membrane made exactly the grown data there
    // (its voxels off the grown data carved, the grown data's voxels filled), and each half
    // of that alone: which of them removes the loop.
    for (const std::array<int, 4>& p : o.probes) {
      std::vector<uint8_t> filled(data_solid.size()), carved(data_solid.size()),
          exact(data_solid.size());
      for (int64_t i = 0; i < data_solid.size(); ++i) {
        const Coord c = data_solid.CoordOf(i);
        const bool in_box = std::abs(c.x - p[0]) <= p[3] && std::abs(c.y - p[1]) <= p[3] &&
                            std::abs(c.z - p[2]) <= p[3];
        const bool m = !IsOutside(vox->grid.at(i));
        const bool g = !IsOutside(data_solid.at(i));
        filled[i] = m || (in_box && g);
        carved[i] = in_box ? m && g : m;
        exact[i] = in_box ? g : m;
      }
      std::vector<std::string> parts;
      for (auto* solid : {&filled, &carved, &exact}) {
        const std::vector<uint8_t> out = OutsideOf(data_solid, *solid);
        int cavities = 0;
        for (int64_t i = 0; i < data_solid.size(); ++i) {
          cavities += (*solid)[i] == 0 && out[i] == 0;
          (*solid)[i] = out[i] == 0;
        }
        const VoxelTopology t = ComputeVoxelTopology(SolidGrid(data_solid, *solid));
        std::vector<int> g = t.genus;
        std::sort(g.begin(), g.end());
        parts.push_back(absl::StrCat(t.shells, "/[", absl::StrJoin(g, ","), "]",
                                     cavities > 0 ? absl::StrCat(" (", cavities, " filled)") : ""));
      }
      absl::StrAppend(&data_note,
                      absl::StrFormat("\n    box (%d, %d, %d) +-%d: data filled %s, off-data "
                                      "carved %s, both %s",
                                      p[0], p[1], p[2], p[3], parts[0], parts[1], parts[2]));
    }
  }
  std::printf("%s%12s %7.3f  %-16s %-16s %s%s%s%s%s%s\n", row.c_str(),
              absl::StrCat(d[0], "x", d[1], "x", d[2]).c_str(), seconds,
              absl::StrCat(topo.shells, " / [", absl::StrJoin(genus, ","), "]").c_str(),
              genus_asserted ? absl::StrCat(expected.shells, " / [",
                                            absl::StrJoin(expected.genus, ","), "]")
                                   .c_str()
                             : absl::StrCat(expected.shells, " / -").c_str(),
              right ? "ok" : "MISS", inv.ok() ? "" : absl::StrCat(" ", inv.ToString()).c_str(),
              RetryNote(result->handle_retry).c_str(), holes_note.c_str(), rerun_note.c_str(),
              data_note.c_str());
  for (const std::array<int, 4>& b : o.slices) {
    if (model != nullptr) PrintCarvedByLabel(vox->grid, b, *model, result->generations);
    PrintSlices(vox->grid, b, model);
  }
  if (!right && o.locate) {
    std::printf("%s", testing::LocateHandlesAndContacts(vox->grid).c_str());
  }
  if (o.locate && o.data_genus >= 0) {
    std::printf("  the grown data's loops and contacts:\n%s",
                testing::LocateHandlesAndContacts(data_solid).c_str());
    for (size_t k = 0; k < piece_solids.size(); ++k) {
      std::printf("  piece %zu's grown data alone, its loops:\n%s", k + 1,
                  testing::LocateHandlesAndContacts(piece_solids[k]).c_str());
    }
  }
  std::fflush(stdout);
  return right;
}

void PrintHeader() {
  std::printf("%-26s %6s %12s %7s  %-16s %-16s %s\n", "cloud", "voxel", "grid", "shrink",
              "shells / genus", "expected", "");
}

// `n` points spread over the faces of `mesh` by area (fixed seed): the reference object
// sampled everywhere, without a scanner's occlusions.
PointCloud SampleMesh(const TriangleMesh& mesh, int n) {
  std::vector<double> cumulative;
  double total = 0;
  for (const auto& f : mesh.faces) {
    const Point3f& a = mesh.vertices[f[0]];
    const Point3f& b = mesh.vertices[f[1]];
    const Point3f& c = mesh.vertices[f[2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2],
                 z = u[0] * v[1] - u[1] * v[0];
    total += 0.5 * std::sqrt(x * x + y * y + z * z);
    cumulative.push_back(total);
  }
  PointCloud cloud;
  cloud.origin = mesh.origin;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < n && total > 0; ++i) {
    const size_t k = std::min(cumulative.size() - 1,
                              static_cast<size_t>(std::lower_bound(cumulative.begin(),
                                                                   cumulative.end(),
                                                                   unit(rng) * total) -
                                                  cumulative.begin()));
    double r1 = unit(rng), r2 = unit(rng);
    if (r1 + r2 > 1) {
      r1 = 1 - r1;
      r2 = 1 - r2;
    }
    const auto& f = mesh.faces[k];
    Point3f p;
    for (int d = 0; d < 3; ++d) {
      p[d] = static_cast<float>(mesh.vertices[f[0]][d] +
                                r1 * (mesh.vertices[f[1]][d] - mesh.vertices[f[0]][d]) +
                                r2 * (mesh.vertices[f[2]][d] - mesh.vertices[f[0]][d]));
    }
    cloud.points.push_back(p);
  }
  return cloud;
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
      absl::StatusOr<TriangleMesh> model = absl::NotFoundError("not read");
      if (!o.slices.empty()) {
        model = ReadMesh(absl::StrCat(o.shared_dir, "/data/models/", m.model, ".obj"));
      }
      for (double f : o.factors) {
        RunOne(o, name, f, *cloud, f * l, m.expected, m.genus_asserted, tally,
               model.ok() ? &*model : nullptr);
      }
      if (o.reference_points > 0 && kind == m.kinds.front()) {
        absl::StatusOr<TriangleMesh> mesh =
            ReadMesh(absl::StrCat(o.shared_dir, "/data/models/", m.model, ".obj"));
        if (!mesh.ok()) continue;
        const PointCloud reference = SampleMesh(*mesh, o.reference_points);
        Tally not_counted;
        for (double f : o.factors) {
          RunOne(o, absl::StrCat(m.model, "-reference"), f, reference, f * l, m.expected,
                 m.genus_asserted, not_counted);
        }
      }
    }
  }
}

// The runs of tests/engine/shrink_topology_test.cc and cup_topology_test.cc.
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
  // Thin-walled open cups (tests/engine/cup_topology_test.cc): walls of 2 to 8 voxels at 1x;
  // a membrane holding half the cylinder's volume or more has its inside filled: a miss.
  for (double wall : {2.0, 3.0, 4.5, 8.0}) {
    const std::string name = absl::StrCat("cup-wall", wall);
    if (!Selected(o, name)) continue;
    const PointCloud cloud = testing::CupCloud(wall, 100000);
    for (double f : o.factors) {
      RunOne(o, name, f, cloud, f * testing::CupVoxelSize(100000), ExpectedTopology("sphere"),
             true, tally, nullptr, 0.5 * testing::CupCylinderVolume());
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

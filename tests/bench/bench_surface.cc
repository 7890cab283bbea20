// bench_surface: the whole membrane reconstruction per real cloud, stage by stage (voxelize,
// shrink, relax, surface, Draco encode), for both surfaces (smooth, cuberille), with the mesh
// checks, the mesh topology against the membrane's, and the accuracy against the reference
// mesh (Chamfer, p95, Hausdorff as % of its bounding-box diagonal, F-score at 1%); Open3D
// Poisson (depth 9) on the same cloud, measured the same way. See README.md.
//
// Every run is core/pipeline's RunReconstruction, the driver `membrane reconstruct` and
// membraned run, with a cloud in memory and a Draco encoding in memory as its ends. Exit
// status 1 when a run fails.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
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
#include "core/io/draco_codec.h"
#include "core/io/mesh_io.h"
#include "core/io/point_cloud_io.h"
#include "core/mesh/mesh_check.h"
#include "core/pipeline/draco_mesh_sink.h"
#include "core/pipeline/in_memory_ends.h"
#include "core/pipeline/membrane_counts.h"
#include "core/pipeline/reconstruction_pipeline.h"
#include "core/pipeline/thread_limits.h"
#include "tests/bench/bench_util.h"
#include "tests/bench/open3d_mesh_peer.h"
#include "tests/bench/open3d_peer.h"
#include "tests/bench/surface_distance.h"

namespace membrane::bench {
namespace {

namespace fs = std::filesystem;

// The default .drc output of `membrane reconstruct`: surfaces are built on its grid, and what
// is measured and checked is the decoded file.
constexpr int kFileBits = 11;
constexpr int kFileCompressionLevel = 7;

struct BenchOptions {
  bool quick = false;
  std::vector<std::string> models;  // substrings of cloud names; empty = all
  std::string shared_dir;
  bool open3d = true;
  bool open3d_variable = false;  // also run Open3D on the *-variable clouds
  int64_t samples = 100'000;
  int threads = 1;  // ReconstructionOptions::threads: the smooth surface's fit and the check
  Open3dPeer peer;
};

constexpr char kUsage[] =
    "usage: bench_surface [--quick] [--models NAME,...] [--shared DIR] [--samples N]\n"
    "                     [--no-open3d] [--open3d-variable] [--python PATH]\n"
    "                     [--open3d-threads N] [--open3d-timeout S] [--threads N]\n"
    "  --quick            one small cloud, 20k samples, no Open3D (the ctest smoke)\n"
    "  --models LIST      clouds whose name contains one of these (e.g. bunny,spot-scan)\n"
    "  --shared DIR       folder holding data/clouds and data/models (default:\n"
    "                     $MEMBRANE_SHARED_DIR, else <repo>/../shared)\n"
    "  --samples N        area-uniform samples per mesh for the distances (default 100000)\n"
    "  --no-open3d        skip the Open3D Poisson peer\n"
    "  --open3d-variable  run Open3D on the *-variable clouds too (fandisk-variable: 700+ s)\n"
    "  --python PATH      interpreter with open3d (default /usr/bin/python3)\n"
    "  --open3d-threads N threads for Open3D (default 1, like the one-core membrane)\n"
    "  --open3d-timeout S stop Open3D after S seconds per cloud (default 0: never)\n"
    "  --threads N        threads of the smooth surface's fit and the mesh check, 1..256\n"
    "                     (default 1; the mesh is the same for any N)\n";

std::optional<BenchOptions> ParseArgs(int argc, char** argv) {
  BenchOptions o;
  const char* env = std::getenv("MEMBRANE_SHARED_DIR");
  o.shared_dir = env != nullptr && *env != '\0' ? env : MEMBRANE_SOURCE_DIR "/../shared";
  o.peer.script = MEMBRANE_BENCH_DIR "/open3d_poisson.py";
  bool samples_given = false;
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
    } else if (arg == "--open3d-variable") {
      o.open3d_variable = true;
    } else if (arg == "--models") {
      auto v = value();
      if (!v) return std::nullopt;
      o.models = absl::StrSplit(*v, ',', absl::SkipEmpty());
    } else if (arg == "--shared") {
      auto v = value();
      if (!v) return std::nullopt;
      o.shared_dir = *v;
    } else if (arg == "--samples") {
      auto v = value();
      if (!v || !absl::SimpleAtoi(*v, &o.samples) || o.samples < 100) return std::nullopt;
      samples_given = true;
    } else if (arg == "--threads") {
      auto v = value();
      if (!v || !absl::SimpleAtoi(*v, &o.threads) || o.threads < 1 ||
          o.threads > kMaxReconstructionThreads)
        return std::nullopt;
    } else if (std::optional<bool> peer_flag = ParseOpen3dFlag(arg, value, o.peer)) {
      if (!*peer_flag) return std::nullopt;
    } else {
      return std::nullopt;
    }
  }
  if (o.quick) {
    o.open3d = false;
    if (!samples_given) o.samples = 20'000;
  }
  return o;
}

// "0" or "0,1,0"; long lists cut after 6 entries.
std::string GenusText(const std::vector<int>& genus) {
  if (genus.size() <= 6) return absl::StrJoin(genus, ",");
  std::vector<int> head(genus.begin(), genus.begin() + 6);
  return absl::StrCat(absl::StrJoin(head, ","), ",..");
}

// The reference model of a cloud: "stanford-bunny-scan" -> "stanford-bunny".
std::string ModelOf(const std::string& cloud) {
  for (const char* suffix : {"-scan", "-variable"}) {
    const std::string s = suffix;
    if (cloud.size() > s.size() && cloud.compare(cloud.size() - s.size(), s.size(), s) == 0) {
      return cloud.substr(0, cloud.size() - s.size());
    }
  }
  return cloud;
}

bool IsVariable(const std::string& cloud) { return cloud.find("-variable") != std::string::npos; }

// ---------------------------------------------------------------------------------------------
// One row: a surface of the membrane, or the Open3D peer.

struct Row {
  std::string cloud;
  std::string kind;  // "smooth", "cuberille", "open3d", or "-" for a cloud that failed early
  bool ok = false;
  std::string error;
  int64_t faces = 0;
  // Membrane surfaces: the mesh check and its shells/genus against the membrane's.
  MeshReport check;
  bool same_topology = false;
  double voxelize_s = 0, shrink_s = 0, relax_s = 0, surface_s = 0, encode_s = 0;
  double total_s = 0;  // the pipeline's whole run (report.seconds.total)
  int64_t draco_bytes = 0;
  double open3d_s = 0;  // Open3D: wall seconds of normals + orientation + Poisson
  bool distances_ok = false;
  SurfaceDistances dist;

  bool AfterShrinkFaster() const { return relax_s + surface_s + encode_s < shrink_s; }
};

const char* YesNo(bool b) { return b ? "yes" : "no"; }

// Same number of shells and the same multiset of genera. The statistics' membrane is counted
// before relaxation, which keeps its topology (only simple voxels move).
bool SameTopology(const MeshReport& r, const MembraneCounts& membrane) {
  std::vector<int> a = r.genus, b = membrane.genus;
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  return r.shells == membrane.shells && a == b;
}

// The grid the mesh was built and encoded on: "11-bit grid", or float32 when on the file's
// grid the check found crossing or flattened faces.
std::string GridText(const QuantizationReport& q) {
  if (q.bits > 0) return absl::StrCat(q.bits, "-bit grid");
  return absl::StrCat("float32 (the ", q.requested_bits, "-bit grid crossed faces)");
}

std::string Num(bool ok, double v) { return ok ? absl::StrFormat("%.3f", v) : std::string("-"); }

void PrintHeader() {
  std::printf("%-24s %-9s %8s %-6s %-5s %6s %6s %6s %6s %8s %7s %7s %7s %7s %6s %7s %6s %7s %6s\n",
              "model", "surface", "faces", "closed", "manif", "shells", "genus", "=memb?",
              "vox s", "shrink s", "relax s", "surf s", "enc s", "total s", "r+s+e<", "Chamf%",
              "p95%", "Hausd%", "F@1%");
}

void PrintRow(const Row& r) {
  if (r.kind == "open3d") return;
  if (r.faces == 0 && !r.ok) {
    std::printf("%-24s %-9s ERROR %s\n", r.cloud.c_str(), r.kind.c_str(), r.error.c_str());
    return;
  }
  const bool d = r.distances_ok;
  std::printf("%-24s %-9s %8lld %-6s %-5s %6d %6s %6s %6.3f %8.3f %7.3f %7.3f %7.3f %7.3f %6s "
              "%7s %6s %7s %6s\n",
              r.cloud.c_str(), r.kind.c_str(), static_cast<long long>(r.faces),
              YesNo(r.check.closed), YesNo(r.check.manifold), r.check.shells,
              GenusText(r.check.genus).c_str(), r.same_topology ? "yes" : "NO", r.voxelize_s,
              r.shrink_s, r.relax_s, r.surface_s, r.encode_s, r.total_s,
              YesNo(r.AfterShrinkFaster()), Num(d, r.dist.chamfer).c_str(),
              Num(d, r.dist.p95).c_str(), Num(d, r.dist.hausdorff).c_str(),
              Num(d, r.dist.fscore).c_str());
}

void PrintOpen3dHeader() {
  std::printf("%-24s %-9s %8s %9s %7s %6s %7s %6s\n", "model", "peer", "faces", "seconds",
              "Chamf%", "p95%", "Hausd%", "F@1%");
}

void PrintOpen3dRow(const Row& r) {
  if (r.kind != "open3d") return;
  if (!r.ok) {
    std::printf("%-24s %-9s %s\n", r.cloud.c_str(), "poisson9", r.error.c_str());
    return;
  }
  const bool d = r.distances_ok;
  std::printf("%-24s %-9s %8lld %9.2f %7s %6s %7s %6s\n", r.cloud.c_str(), "poisson9",
              static_cast<long long>(r.faces), r.open3d_s, Num(d, r.dist.chamfer).c_str(),
              Num(d, r.dist.p95).c_str(), Num(d, r.dist.hausdorff).c_str(),
              Num(d, r.dist.fscore).c_str());
}

// Fills r.dist from the comparison of `mesh` with `reference`, printing the one-way details.
void Measure(const BenchOptions& o, const TriangleMesh& mesh, const TriangleMesh& reference,
             Row& r) {
  const double t = Now();
  absl::StatusOr<SurfaceDistances> d = CompareSurfaces(mesh, reference, o.samples);
  if (!d.ok()) {
    std::printf("  %-9s distances: %s\n", r.kind.c_str(), d.status().ToString().c_str());
    return;
  }
  r.dist = *d;
  r.distances_ok = true;
  std::printf("  %-9s mean recon->ref %.3f%%, ref->recon %.3f%%, precision %.3f, recall %.3f "
              "(1%% of the diagonal = %.4g; measured in %.1f s)\n",
              r.kind.c_str(), r.dist.to_reference, r.dist.to_recon, r.dist.precision,
              r.dist.recall, r.dist.diagonal / 100.0, Now() - t);
}

// ---------------------------------------------------------------------------------------------
// One cloud

// The rows of `file`: smooth, cuberille, and open3d when `run_open3d`. Sets `failed` when a
// stage returned an error.
std::vector<Row> RunCloud(const BenchOptions& o, const fs::path& file, bool run_open3d,
                          const std::string& open3d_skip_reason, bool& failed) {
  std::vector<Row> rows;
  const std::string name = file.stem().string();
  const fs::path ref_path = fs::path(o.shared_dir) / "data" / "models" / (ModelOf(name) + ".obj");
  std::printf("\n== %s (reference %s)\n", name.c_str(), ref_path.string().c_str());
  auto fail = [&](const std::string& what, const absl::Status& s) {
    Row r;
    r.cloud = name;
    r.kind.assign(1, '-');  // (assigning "-" trips GCC 12's -Wrestrict false positive)
    r.error = absl::StrCat(what, ": ", s.ToString());
    std::printf("ERROR %s\n", r.error.c_str());
    rows.push_back(r);
    failed = true;
    return rows;
  };

  absl::StatusOr<PointCloud> cloud = ReadPointCloud(file.string());
  if (!cloud.ok()) return fail("read cloud", cloud.status());
  absl::StatusOr<TriangleMesh> reference = ReadMesh(ref_path.string());
  if (!reference.ok()) return fail("read reference", reference.status());
  const MeshReport ref_check = CheckMesh(*reference);
  std::printf("reference: %lld faces, closed %s, %d shell(s), %lld boundary edges (reported, "
              "not judged)\n",
              static_cast<long long>(ref_check.faces), YesNo(ref_check.closed), ref_check.shells,
              static_cast<long long>(ref_check.boundary_edges));

  const auto row_failed = [&](Row& r, const std::string& error) {
    r.error = error;
    std::printf("ERROR %s\n", r.error.c_str());
    rows.push_back(r);
    failed = true;
  };
  // Each surface is a whole run of the pipeline users run (`membrane reconstruct --local` to
  // a .drc file), from this cloud in memory to a Draco encoding in memory.
  bool described = false;
  for (const std::string kind : {"smooth", "cuberille"}) {
    Row r;
    r.cloud = name;
    r.kind = kind;
    ReconstructionOptions options;  // formula (1), default shrink, relaxation on
    options.surface = kind == "smooth" ? SurfaceKind::kSmooth : SurfaceKind::kCuberille;
    options.output_quantization_bits = kFileBits;
    options.threads = o.threads;
    InMemoryCloudSource source(*cloud);
    NoResourceLimit gate;
    DracoMeshSink sink(kFileCompressionLevel);
    NullReconstructionObserver observer;
    absl::StatusOr<ReconstructionReport> report = RunReconstruction(
        options, {source, gate, sink, observer}, ErrorContext{}, CancelToken::Never());
    if (!report.ok()) {
      row_failed(r, absl::StrCat("reconstruction: ", report.status().ToString()));
      continue;
    }
    const ReconstructionReport& rep = *report;
    if (!described) {
      described = true;
      std::printf("points %lld, grid %dx%dx%d with padding, voxel %.5g; relaxation +%lld -%lld "
                  "voxels; membrane: %d shell(s), genus %s\n",
                  static_cast<long long>(rep.points), rep.grid[0], rep.grid[1], rep.grid[2],
                  rep.voxel_size, static_cast<long long>(rep.relaxation.phase1_moves),
                  static_cast<long long>(rep.relaxation.phase2_moves), rep.membrane.shells,
                  GenusText(rep.membrane.genus).c_str());
    }
    r.voxelize_s = rep.seconds.voxelize;
    r.shrink_s = rep.seconds.shrink;
    r.relax_s = rep.seconds.relax;
    r.surface_s = rep.seconds.surface;
    r.encode_s = rep.seconds.encode;
    r.total_s = rep.seconds.total;
    const std::string file = sink.TakeBytes();
    r.draco_bytes = static_cast<int64_t>(file.size());
    absl::StatusOr<TriangleMesh> mesh = DecodeDracoMesh(file);
    if (!mesh.ok()) {
      row_failed(r, absl::StrCat("draco: ", mesh.status().ToString()));
      continue;
    }
    r.ok = true;
    r.check = CheckMesh(*mesh);
    r.faces = r.check.faces;
    r.same_topology = SameTopology(r.check, rep.membrane);
    std::printf("  %-9s %lld faces, draco %lld bytes, %s; oriented %s, self-intersections %lld, "
                "positive volume %s, boundary edges %lld, genus %s\n",
                kind.c_str(), static_cast<long long>(r.faces),
                static_cast<long long>(r.draco_bytes), GridText(rep.quantization).c_str(),
                YesNo(r.check.oriented), static_cast<long long>(r.check.self_intersections),
                YesNo(r.check.positive_volume), static_cast<long long>(r.check.boundary_edges),
                GenusText(r.check.genus).c_str());
    Measure(o, *mesh, *reference, r);
    rows.push_back(r);
  }
  // The membrane is done: free the points before Open3D runs.
  cloud->points = {};

  if (!run_open3d) {
    std::printf("  open3d    not run: %s\n", open3d_skip_reason.c_str());
    return rows;
  }
  std::fflush(stdout);
  Row r;
  r.cloud = name;
  r.kind = "open3d";
  absl::StatusOr<Open3dMeshRun> peer = RunOpen3dPoissonMesh(o.peer, file.string(), 9);
  if (!peer.ok()) {
    r.error = absl::StrCat("FAILED: ", peer.status().ToString());
    std::printf("  open3d    %s\n", r.error.c_str());
    rows.push_back(r);
    return rows;  // the peer failing is reported, not a failure of the membrane
  }
  r.ok = true;
  r.open3d_s = peer->run.seconds;
  r.faces = static_cast<int64_t>(peer->mesh.faces.size());
  std::printf("  open3d    %s\n", peer->run.json.c_str());
  Measure(o, peer->mesh, *reference, r);
  rows.push_back(r);
  return rows;
}

// ---------------------------------------------------------------------------------------------

int Main(int argc, char** argv) {
  std::optional<BenchOptions> parsed = ParseArgs(argc, argv);
  if (!parsed) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  const BenchOptions& o = *parsed;
  const std::time_t now = std::time(nullptr);
  char date[64];
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M:%S", std::localtime(&now));
  std::printf("bench_surface%s: %s, %ld online CPUs, load average %s\n", o.quick ? " --quick" : "",
              date, sysconf(_SC_NPROCESSORS_ONLN), LoadAverage().c_str());
  std::printf("each surface one run of the reconstruction pipeline: formula-(1) voxel size, "
              "default shrink, relaxation on (threshold 13), one thread (the smooth surface's "
              "fit and the mesh check: %d); surfaces on the %d-bit grid of the .drc output, "
              "encode = Draco on that grid, level %d, beside the check; total = the whole run; "
              "checks and distances on the decoded file, distances on %lld area-uniform "
              "samples per mesh, %% of the reference mesh's bounding-box diagonal; shared dir "
              "%s\n",
              o.threads, kFileBits, kFileCompressionLevel, static_cast<long long>(o.samples),
              o.shared_dir.c_str());

  const fs::path clouds = fs::path(o.shared_dir) / "data" / "clouds";
  std::error_code ec;
  if (!fs::is_directory(clouds, ec)) {
    std::printf("SKIPPED: %s is absent (set MEMBRANE_SHARED_DIR or --shared)\n",
                clouds.string().c_str());
    return 0;
  }
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(clouds, ec)) {
    if (e.path().extension() == ".ply") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  if (o.quick) {  // one small cloud: the first 100k variable-density one
    auto it = std::find_if(files.begin(), files.end(),
                           [](const fs::path& p) { return IsVariable(p.stem().string()); });
    files = it == files.end() ? std::vector<fs::path>{} : std::vector<fs::path>{*it};
  }
  if (!o.models.empty()) {
    std::erase_if(files, [&](const fs::path& p) {
      const std::string n = p.stem().string();
      return std::none_of(o.models.begin(), o.models.end(),
                          [&](const std::string& m) { return n.find(m) != std::string::npos; });
    });
  }
  if (files.empty()) {
    std::printf("SKIPPED: no selected cloud in %s\n", clouds.string().c_str());
    return 0;
  }

  bool open3d_available = false;
  std::string open3d_note = o.quick ? "--quick" : "--no-open3d";
  if (o.open3d) {
    absl::StatusOr<std::string> v = Open3dVersion(o.peer);
    open3d_available = v.ok();
    open3d_note = v.ok() ? std::string() : std::string(v.status().message());
    if (v.ok()) {
      std::printf("open3d %s via %s, %d thread(s), screened Poisson depth 9 after KNN-30 normals "
                  "and consistent orientation; mesh not clipped%s\n",
                  v->c_str(), o.peer.python.c_str(), o.peer.threads,
                  o.open3d_variable ? ""
                                    : "; NOT run on the *-variable clouds (fandisk-variable alone "
                                      "takes 700+ s; --open3d-variable runs them)");
    } else {
      std::printf("open3d not available: %s\n", open3d_note.c_str());
    }
  }

  bool failed = false;
  std::vector<Row> all;
  for (const fs::path& f : files) {
    const std::string name = f.stem().string();
    const bool variable_skip = IsVariable(name) && !o.open3d_variable;
    const bool run_open3d = o.open3d && open3d_available && !variable_skip;
    const std::string reason =
        !o.open3d ? open3d_note
        : !open3d_available ? absl::StrCat("unavailable (", open3d_note, ")")
                            : std::string("*-variable cloud (--open3d-variable runs it)");
    std::vector<Row> rows = RunCloud(o, f, run_open3d, reason, failed);
    PrintHeader();
    for (const Row& r : rows) PrintRow(r);
    if (run_open3d) {
      PrintOpen3dHeader();
      for (const Row& r : rows) PrintOpen3dRow(r);
    }
    all.insert(all.end(), rows.begin(), rows.end());
    std::fflush(stdout);
  }

  std::printf("\n== summary (seconds wall, one thread, the smooth fit %d; distances %% of the "
              "reference diagonal; r+s+e< = relax + surface + encode < shrink; =memb? = shells and "
              "genus of the mesh equal the membrane's)\n",
              o.threads);
  PrintHeader();
  for (const Row& r : all) PrintRow(r);
  if (std::any_of(all.begin(), all.end(), [](const Row& r) { return r.kind == "open3d"; })) {
    std::printf("\n== summary: Open3D screened Poisson depth 9 (seconds = normals + orientation "
                "+ Poisson, wall; mesh as is, not clipped)\n");
    PrintOpen3dHeader();
    for (const Row& r : all) PrintOpen3dRow(r);
  }
  std::printf("load average at the end: %s\n", LoadAverage().c_str());
  return failed ? 1 : 0;
}

}  // namespace
}  // namespace membrane::bench

int main(int argc, char** argv) { return membrane::bench::Main(argc, argv); }

#include "client/reconstruct_command.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "CLI/CLI.hpp"
#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/time/time.h"
#include "client/deadline_timer.h"
#include "client/flag_checks.h"
#include "client/format_flags.h"
#include "client/interrupt_watch.h"
#include "client/local_reconstruction.h"
#include "client/output_files.h"
#include "client/progress_printer.h"
#include "client/remote_reconstruction.h"
#include "client/report_text.h"
#include "client/server_connection.h"
#include "client/std_streams.h"
#include "client/upload_plan.h"
#include "core/engine/plate_schedule.h"
#include "core/io/file_format.h"
#include "core/mesh/mesh_decimation.h"
#include "core/pipeline/machine_memory.h"
#include "core/pipeline/stats_json.h"
#include "core/pipeline/thread_limits.h"

namespace membrane::client {
namespace {

constexpr int64_t kMaxInitialPlate = 100000;  // ValidateShrinkOptions' bound
constexpr int64_t kMaxVoxelBudget = 1'000'000'000'000;
constexpr int64_t kMaxMemoryLimit = int64_t{1} << 60;
constexpr double kMaxTimeoutSeconds = 1e6;
constexpr int64_t kMaxTargetFaces = int64_t{1} << 31;  // faces are indexed by int32

// The values as parsed, before validation: wide types, so that an out-of-range value reaches
// our range check (and its message) instead of failing conversion.
struct ReconstructFlags {
  std::string input;
  std::string input_format;
  bool drop_invalid = false;
  std::string output;
  std::string output_format;
  bool local = false;
  ConnectionFlags connection;
  double voxel_size = 0;
  int64_t initial_plate = 0;
  std::string schedule = "halving";
  std::string surface = "smooth";
  bool no_relax = false;
  int64_t quantization = kDefaultUploadBits;
  bool quantization_given = false;
  int64_t compression_level = 7;
  int64_t voxel_budget = 0;   // 0: no cap in voxels (the memory limit decides)
  int64_t memory_limit = -1;  // -1: what the machine has available
  std::string stats_json;
  double timeout = 0;
  bool quiet = false;
  int64_t threads = 0;
  int64_t target_faces = 0;       // 0: not given
  int64_t drop_after_events = 0;  // test hook of --server; see RemoteParams
  double progress_after = 1;      // test hook: ProgressPrinter::set_progress_after
  std::string on_interrupt = "leave";
};

void DefineFlags(CLI::App& app, ReconstructFlags& f) {
  app.add_option("INPUT", f.input,
                 "point cloud: .ply .obj .off .xyz .txt .pts .pcd .drc, or - for standard input")
      ->required();
  app.add_option("--input-format", f.input_format,
                 "the input's format when its name does not say it: ply obj off xyz pcd drc; "
                 "for - (standard input) it is otherwise told from the first bytes");
  app.add_flag("--drop-invalid", f.drop_invalid,
               "leave out the points with NaN or infinite coordinates (how organized scans mark "
               "pixels without a return) instead of refusing the cloud; the count is reported");
  app.add_option("-o,--output", f.output,
                 "mesh to write: .ply .obj .stl .drc, or - for standard output (then the table "
                 "and the summary go to stderr)")
      ->required();
  app.add_option("--output-format", f.output_format,
                 "the mesh's format when the name does not say it: ply obj stl drc; for - it is "
                 "otherwise binary PLY");
  CLI::Option* local = app.add_flag("--local", f.local, "run the reconstruction in this process");
  // --server is the default unless --local.
  local->excludes(AddConnectionFlags(app, f.connection));
  app.add_option("--voxel-size", f.voxel_size,
                 "voxel edge in model units; 0 = the paper's formula (1), or coarser where the "
                 "points scatter across their surface by more than 0.15 of it")
      ->capture_default_str();
  app.add_option("--initial-plate", f.initial_plate,
                 "first plate size in voxels, [0, 100000]; 0 = from the grid")
      ->capture_default_str();
  app.add_option("--schedule", f.schedule, "plate sizes: halving or linear")->capture_default_str();
  app.add_option("--surface", f.surface, "smooth (fitted to the points) or cuberille (voxel faces)")
      ->capture_default_str();
  app.add_flag("--no-relax", f.no_relax, "skip the membrane relaxation (paper section 5)");
  app.add_option("--quantization", f.quantization,
                 "Draco position bits of the cloud sent to --server and of .drc output, [0, 30]; "
                 "0 = lossless; when not given, the cloud sent gets more bits where its voxel "
                 "needs them (a step of at most 1/8 voxel), and so does the mesh (a step of at "
                 "most 1/32 voxel: 13 bits on the grids of 100k-point clouds)")
      ->capture_default_str()
      ->each([&f](const std::string&) { f.quantization_given = true; });
  app.add_option("--compression-level", f.compression_level,
                 "Draco compression level of the cloud sent and of .drc output, [0, 10]")
      ->capture_default_str();
  app.add_option("--target-faces", f.target_faces,
                 "decimate the mesh to at most this many faces (>= 4), keeping it closed, "
                 "manifold, uncrossed and of the same topology; the summary gives the error "
                 "added; 0 = the surface as built")
      ->capture_default_str();
  app.add_option("--voxel-budget", f.voxel_budget,
                 "largest voxel grid to allocate (padding included); 0 (default) = no cap in "
                 "voxels: the memory the run needs by its estimates decides (--memory-limit, "
                 "or the server's memory budget)")
      ->capture_default_str();
  app.add_option("--memory-limit", f.memory_limit,
                 "with --local: most bytes the run may need by its estimates, checked before "
                 "the grid and before the surface; -1 (default) = the memory this machine (or "
                 "its container) has available; 0 = no limit")
      ->needs(local);
  app.add_option("--stats-json", f.stats_json,
                 "write the statistics JSON to this file, or - for standard output");
  app.add_option("--timeout", f.timeout, "give up after this many seconds (exit 4); 0 = never")
      ->capture_default_str();
  app.add_flag("-q,--quiet", f.quiet,
               "no progress lines on stderr and no generation table on stdout (the summary "
               "line and errors stay)");
  app.add_option("--threads", f.threads,
                 "with --local: threads of the voxelization, the relaxation, the surface and the "
                 "mesh check, [0, 256]; 0 = the "
                 "cores of this machine (the mesh is the same for any value)")
      ->capture_default_str()
      ->needs(local);
  app.add_option("--on-interrupt", f.on_interrupt,
                 "with --server, what Ctrl-C does to an accepted job: leave it running (and "
                 "print the `membrane jobs watch` command that gets its mesh) or cancel it")
      ->check(CLI::IsMember({"leave", "cancel"}))
      ->capture_default_str();
  // Hidden (empty group): lets the tests drop a --server call midway to exercise re-attaching.
  app.add_option("--drop-after-events", f.drop_after_events)->group("");
  // Hidden: lets the tests see every stage's progress, however short the stage.
  app.add_option("--progress-after", f.progress_after)->group("");
}

// The values whose check needs no parsing, in the order of --help; the first failure wins.
absl::Status CheckFlagValues(const ReconstructFlags& f) {
  const absl::Status checks[] = {
      // Unknown extensions and missing directories fail here, before minutes of work.
      // Standard input's format may have to wait for its first bytes.
      IsStdStream(f.input) && f.input_format.empty()
          ? absl::OkStatus()
          : InputFormat(f.input, f.input_format, FileUse::kReadPointCloud).status(),
      OutputFormat(f.output, f.output_format, FileUse::kWriteMesh).status(),
      CheckOutputPath("-o", f.output),
      IsStdStream(f.output) && IsStdStream(f.stats_json)
          ? absl::InvalidArgumentError(
                "-o - and --stats-json - would both write to standard output; send one of "
                "them to a file")
          : absl::OkStatus(),
      std::isfinite(f.voxel_size) && f.voxel_size >= 0
          ? absl::OkStatus()
          : absl::InvalidArgumentError(absl::StrFormat(
                "--voxel-size %g must be positive (model units), or 0 for the default "
                "(formula (1), coarser for noisy points)",
                f.voxel_size)),
      CheckIntRange("--initial-plate", f.initial_plate, 0, kMaxInitialPlate),
      CheckIntRange("--quantization", f.quantization, 0, 30, "0 = lossless"),
      CheckIntRange("--compression-level", f.compression_level, 0, 10),
      f.target_faces == 0 ? absl::OkStatus()
                          : CheckIntRange("--target-faces", f.target_faces, kMinTargetFaces,
                                          kMaxTargetFaces, "0 = no decimation"),
      CheckIntRange("--voxel-budget", f.voxel_budget, 0, kMaxVoxelBudget, "0 = no cap"),
      CheckIntRange("--memory-limit", f.memory_limit, -1, kMaxMemoryLimit,
                    "-1 = what is available, 0 = no limit"),
      f.stats_json.empty() ? absl::OkStatus() : CheckOutputPath("--stats-json", f.stats_json),
      CheckRealRange("--timeout", f.timeout, 0, kMaxTimeoutSeconds, "seconds; 0 = no limit"),
      CheckIntRange("--threads", f.threads, 0, kMaxReconstructionThreads, "0 = the cores"),
  };
  for (const absl::Status& s : checks) {
    if (!s.ok()) return s;
  }
  return absl::OkStatus();
}

absl::StatusOr<ReconstructionParams> ParamsFromFlags(const ReconstructFlags& f) {
  if (absl::Status s = CheckFlagValues(f); !s.ok()) return s;
  absl::StatusOr<PlateSchedule> schedule = ParsePlateSchedule(f.schedule);
  if (!schedule.ok()) {
    return absl::InvalidArgumentError(
        absl::StrCat("--schedule '", f.schedule, "' is not one of: halving, linear"));
  }
  absl::StatusOr<SurfaceKind> surface = ParseSurfaceKind(f.surface);
  if (!surface.ok()) return surface.status();
  ReconstructionParams p;
  p.input = f.input;
  p.input_format = f.input_format;
  p.invalid_points = f.drop_invalid ? InvalidPoints::kDrop : InvalidPoints::kRefuse;
  p.output = f.output;
  // Checked by CheckFlagValues.
  p.output_format = *OutputFormat(f.output, f.output_format, FileUse::kWriteMesh);
  p.options.voxelize.voxel_size = f.voxel_size;
  p.options.voxelize.voxel_budget = f.voxel_budget;
  p.options.shrink.initial_plate = static_cast<int>(f.initial_plate);
  p.options.shrink.schedule = *schedule;
  p.options.relax = !f.no_relax;
  p.options.surface = *surface;
  p.options.target_faces = f.target_faces;
  p.options.threads = f.threads > 0 ? static_cast<int>(f.threads) : MachineThreads();
  // Read only for --local: the limit does not apply to --server runs.
  if (f.local) {
    p.memory_limit_bytes =
        f.memory_limit >= 0 ? f.memory_limit : ReadMachineMemory().available_bytes;
  }
  p.draco.position_quantization_bits = static_cast<int>(f.quantization);
  p.draco.compression_level = static_cast<int>(f.compression_level);
  // Only .drc quantizes; the surface is then built and checked on the file's grid.
  if (p.output_format == FileFormat::kDrc) {
    p.options.output_quantization_bits = static_cast<int>(f.quantization);
    p.options.output_bits_follow_voxel = !f.quantization_given;
  }
  return p;
}

// What the user must hear when the mesh breaks its promise (closed, manifold, oriented).
absl::Status SurfaceCheckStatus(const MeshReport& m, const std::string& output) {
  std::string failed;
  if (!m.closed) absl::StrAppend(&failed, failed.empty() ? "" : ", ", "not closed");
  if (!m.manifold) absl::StrAppend(&failed, failed.empty() ? "" : ", ", "not manifold");
  if (!m.oriented) absl::StrAppend(&failed, failed.empty() ? "" : ", ", "not oriented");
  if (failed.empty()) return absl::OkStatus();
  return absl::InternalError(
      absl::StrCat("the surface is ", failed, " (written to ", output, " all the same)"));
}

// The job's parameters as the server takes them. The mesh comes back lossless unless the
// output is .drc, so that a .ply/.obj/.stl holds exactly what the server built.
RemoteParams RemoteParamsFromFlags(const ReconstructFlags& f, FileFormat output_format,
                                   ServerConnection server) {
  RemoteParams r;
  r.server = std::move(server);
  r.input = f.input;
  r.input_format = f.input_format;
  r.invalid_points = f.drop_invalid ? InvalidPoints::kDrop : InvalidPoints::kRefuse;
  r.output = f.output;
  r.output_format = output_format;
  v1::Parameters& p = r.parameters;
  p.set_voxel_size(f.voxel_size);
  p.set_initial_plate(static_cast<int32_t>(f.initial_plate));
  p.set_schedule(f.schedule);
  p.set_surface(f.surface);
  p.set_no_relax(f.no_relax);
  if (f.target_faces > 0) p.set_target_faces(f.target_faces);
  const bool drc_output = output_format == FileFormat::kDrc;
  // Unset leaves the mesh's bits to the server, which chooses them as --local does.
  if (!drc_output) {
    p.set_quantization(0);
  } else if (f.quantization_given) {
    p.set_quantization(static_cast<int32_t>(f.quantization));
  }
  p.set_compression_level(static_cast<int32_t>(f.compression_level));
  // 0 asks for the server's own; the server caps a budget with its own.
  p.set_voxel_budget(f.voxel_budget);
  r.upload.position_quantization_bits = static_cast<int>(f.quantization);
  r.adapt_upload_bits = !f.quantization_given;
  r.upload.compression_level = static_cast<int>(f.compression_level);
  if (f.timeout > 0) r.timeout = absl::Seconds(f.timeout);
  r.drop_after_events = static_cast<int>(f.drop_after_events);
  return r;
}

// Prints a finished run's generation table (unless --quiet), its summary line and its
// warnings, and writes its statistics (--stats-json). The table and the summary go to stdout,
// or to stderr when stdout carries the mesh or the statistics (-o -, --stats-json -).
absl::Status ReportRun(const ReconstructFlags& flags,
                       const std::vector<GenerationStats>& generations,
                       const std::string& summary, const std::vector<std::string>& warnings,
                       const std::string& statistics_json) {
  std::FILE* text = IsStdStream(flags.output) || IsStdStream(flags.stats_json) ? stderr : stdout;
  if (!flags.quiet) std::fputs(GenerationTable(generations).c_str(), text);
  std::fputs(summary.c_str(), text);
  std::fflush(text);
  std::fputs(WarningLines(warnings).c_str(), stderr);
  if (flags.stats_json.empty()) return absl::OkStatus();
  return WriteOutputBytes(flags.stats_json, statistics_json);
}

absl::Status RunRemote(const ReconstructFlags& flags, FileFormat output_format) {
  absl::StatusOr<ServerConnection> server = LoadServerConnection(flags.connection);
  if (!server.ok()) return server.status();
  absl::StatusOr<RemoteOutcome> outcome;
  {
    // Before any thread starts: see InterruptWatch.
    InterruptWatch interrupts(*server, flags.output, flags.on_interrupt == "cancel");
    RemoteParams params = RemoteParamsFromFlags(flags, output_format, *std::move(server));
    params.on_accepted = [&interrupts](const std::string& id) { interrupts.JobAccepted(id); };
    ProgressPrinter progress(stderr, ProgressPrinter::StderrMode(flags.quiet));
    progress.set_progress_after(flags.progress_after);
    outcome = RunRemoteReconstruction(params, progress);
  }
  if (!outcome.ok()) return outcome.status();
  if (absl::Status s = ReportRun(flags, outcome->generations, RemoteSummaryLine(*outcome),
                                 outcome->warnings, outcome->statistics_json);
      !s.ok()) {
    return s;
  }
  return SurfaceCheckStatus(outcome->mesh, OutputName(flags.output));
}

absl::Status RunReconstruct(const ReconstructFlags& flags) {
  absl::StatusOr<ReconstructionParams> params = ParamsFromFlags(flags);
  if (!params.ok()) return params.status();
  if (!flags.local) return RunRemote(flags, params->output_format);

  CancelToken cancel;
  absl::StatusOr<ReconstructionReport> report;
  bool timed_out = false;
  {
    // The printer ends its live line before any error line is printed by main.
    ProgressPrinter progress(stderr, ProgressPrinter::StderrMode(flags.quiet));
    progress.set_progress_after(flags.progress_after);
    DeadlineTimer timer(flags.timeout, &cancel);
    report = RunLocalReconstruction(*params, cancel, progress);
    timed_out = timer.expired();
  }
  if (!report.ok()) {
    if (timed_out) {
      return absl::DeadlineExceededError(absl::StrFormat("timed out after %g s", flags.timeout));
    }
    return report.status();
  }
  if (absl::Status s = ReportRun(flags, report->generations, SummaryLine(*report),
                                 report->warnings, StatsJson(*report));
      !s.ok()) {
    return s;
  }
  return SurfaceCheckStatus(report->mesh, OutputName(flags.output));
}

}  // namespace

Command AddReconstructCommand(CLI::App& parent) {
  CLI::App* app =
      parent.add_subcommand("reconstruct", "reconstruct a closed triangle mesh from a point cloud");
  // Shared with the action: CLI11 writes the parsed values into it.
  auto flags = std::make_shared<ReconstructFlags>();
  DefineFlags(*app, *flags);
  return Command{app, [flags] { return RunReconstruct(*flags); }};
}

}  // namespace membrane::client

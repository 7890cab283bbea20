#include "client/synth_command.h"

#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>

#include "CLI/CLI.hpp"
#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "client/flag_checks.h"
#include "client/format_flags.h"
#include "client/output_files.h"
#include "client/std_streams.h"
#include "core/io/file_format.h"
#include "core/synth/shape_catalog.h"
#include "core/synth/synthesize.h"

namespace membrane::client {
namespace {

// Parsed values; wide integer types so that out-of-range values reach CheckIntRange.
struct SynthFlags {
  std::string shape;
  std::string output;
  std::string output_format;
  int64_t points = 100000;
  double density_ratio = 1.0;
  int64_t holes = 0;
  double noise = 0.0;
  int64_t seed = 1;  // signed: CLI11 would wrap "-1" into a huge unsigned seed
  double voxel_size = 0.0;
  int64_t hole_size = 1;
};

void DefineFlags(CLI::App& app, SynthFlags& f) {
  app.add_option("SHAPE", f.shape, absl::StrCat("one of: ", absl::StrJoin(SynthShapeNames(), ", ")))
      ->required();
  app.add_option("-o,--output", f.output,
                 "point cloud to write: .ply (binary) .xyz .obj .drc, or - for standard output")
      ->required();
  app.add_option("--output-format", f.output_format,
                 "the cloud's format when -o's name does not say it: ply xyz obj drc; for - it "
                 "is otherwise binary PLY");
  app.add_option("--points", f.points, "number of points, [1, 50000000]")->capture_default_str();
  app.add_option("--density-ratio", f.density_ratio,
                 "densest : sparsest surface density, [1, 1000]")
      ->capture_default_str();
  app.add_option("--holes", f.holes, "unsampled patches (smooth shapes), [0, 100]")
      ->capture_default_str();
  app.add_option("--noise", f.noise, "normal noise sigma in model units, [0, 0.1]")
      ->capture_default_str();
  app.add_option("--seed", f.seed, "seed of every random choice")->capture_default_str();
  app.add_option("--voxel-size", f.voxel_size,
                 "cube-pinholes: voxel edge the cloud is built for, [0.001, 1]; 0 = automatic")
      ->capture_default_str();
  app.add_option("--hole-size", f.hole_size, "cube-pinholes: hole side in voxels, >= 1")
      ->capture_default_str();
}

absl::StatusOr<SynthOptions> OptionsFromFlags(const SynthFlags& f) {
  if (!IsSynthShape(f.shape)) {
    return absl::InvalidArgumentError(absl::StrCat(
        "shape '", f.shape, "' is not one of: ", absl::StrJoin(SynthShapeNames(), ", ")));
  }
  const absl::Status checks[] = {
      CheckIntRange("--points", f.points, kMinSynthPoints, kMaxSynthPoints),
      CheckRealRange("--density-ratio", f.density_ratio, 1.0, kMaxDensityRatio),
      CheckIntRange("--holes", f.holes, 0, kMaxHoles),
      CheckRealRange("--noise", f.noise, 0.0, kMaxNoise),
      f.voxel_size == 0.0 ? absl::OkStatus()
                          : CheckRealRange("--voxel-size", f.voxel_size, kMinCubeVoxelSize,
                                           kMaxCubeVoxelSize, "or 0 for automatic"),
      CheckIntRange("--hole-size", f.hole_size, 1, kMaxCubeHoleSize),
      CheckIntRange("--seed", f.seed, 0, std::numeric_limits<int64_t>::max()),
  };
  for (const absl::Status& s : checks) {
    if (!s.ok()) return s;
  }
  SynthOptions o;
  o.shape = f.shape;
  o.points = f.points;
  o.density_ratio = f.density_ratio;
  o.holes = static_cast<int>(f.holes);
  o.noise = f.noise;
  o.seed = static_cast<uint64_t>(f.seed);
  o.voxel_size = f.voxel_size;
  o.hole_size = static_cast<int>(f.hole_size);
  return o;
}

absl::Status RunSynth(const SynthFlags& flags) {
  absl::StatusOr<SynthOptions> options = OptionsFromFlags(flags);
  if (!options.ok()) return options.status();
  // An unsupported extension fails before the (possibly long) generation.
  absl::StatusOr<FileFormat> format =
      OutputFormat(flags.output, flags.output_format, FileUse::kWritePointCloud);
  if (!format.ok()) return format.status();
  if (absl::Status s = CheckOutputPath("-o", flags.output); !s.ok()) return s;
  absl::StatusOr<PointCloud> cloud = SynthesizeShape(*options);
  if (!cloud.ok()) return cloud.status();
  if (absl::Status s = WriteOutputCloud(*cloud, flags.output, *format); !s.ok()) return s;
  // Standard output carries the cloud: the line goes to stderr then.
  std::fprintf(IsStdStream(flags.output) ? stderr : stdout, "wrote %zu points of %s to %s\n",
               cloud->points.size(), flags.shape.c_str(), OutputName(flags.output).c_str());
  return absl::OkStatus();
}

}  // namespace

Command AddSynthCommand(CLI::App& parent) {
  CLI::App* app =
      parent.add_subcommand("synth", "write a synthetic point cloud with a known topology");
  auto flags = std::make_shared<SynthFlags>();
  DefineFlags(*app, *flags);
  return Command{app, [flags] { return RunSynth(*flags); }};
}

}  // namespace membrane::client

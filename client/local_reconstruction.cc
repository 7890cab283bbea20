#include "client/local_reconstruction.h"

#include <optional>
#include <string>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "client/cloud_origin.h"
#include "client/input_file_source.h"
#include "client/input_files.h"
#include "client/memory_limit_gate.h"
#include "client/mesh_file_sink.h"
#include "core/pipeline/reconstruction_pipeline.h"

namespace membrane::client {
namespace {

// The printer's lines, but for the decode stage's: a local run names its input file, the
// shift its reader gave a georeferenced cloud, and the points --drop-invalid left out.
class LocalProgress : public ReconstructionObserver {
 public:
  LocalProgress(ProgressPrinter& printer, const std::string& input, const InputFileSource& source)
      : printer_(printer), input_(input), source_(source) {}

  void StageStarted(PipelineStage stage, const ReconstructionReport& report) override {
    if (stage != PipelineStage::kDecode) return printer_.StageStarted(stage, report);
    printer_.Begin(absl::StrCat("decode: reading ", input_));
  }
  void GenerationFinished(const GenerationStats& generation, int planned_generations) override {
    printer_.GenerationFinished(generation, planned_generations);
  }
  std::optional<ProgressSchedule> progress_schedule() const override {
    return printer_.progress_schedule();
  }
  void StageProgress(PipelineStage stage, std::optional<double> fraction,
                     double seconds) override {
    printer_.StageProgress(stage, fraction, seconds);
  }
  void StageFinished(PipelineStage stage, double seconds,
                     const ReconstructionReport& report) override {
    if (stage != PipelineStage::kDecode) return printer_.StageFinished(stage, seconds, report);
    const size_t count = source_.dropped();
    const std::string dropped =
        count > 0 ? absl::StrCat(" (", DroppedPointsNote(count), ")") : std::string();
    printer_.Finish(absl::StrFormat("decode: %d points%s%s in %.3f s", report.points,
                                    OriginNote(report.origin), dropped, seconds));
  }

 private:
  ProgressPrinter& printer_;
  const std::string& input_;
  const InputFileSource& source_;
};

}  // namespace

absl::StatusOr<ReconstructionReport> RunLocalReconstruction(const ReconstructionParams& params,
                                                            const CancelToken& cancel,
                                                            ProgressPrinter& progress) {
  InputFileSource source(params.input, params.input_format, params.invalid_points);
  MemoryLimitGate gate(params.memory_limit_bytes, params.options.output_quantization_bits);
  MeshFileSink sink(params.output, params.output_format, params.draco.compression_level);
  const std::string input_name = InputName(params.input);
  LocalProgress observer(progress, input_name, source);
  const ErrorContext errors{
      .invalid_argument_prefix = absl::StrCat(input_name, ": "),
      .resource_exhausted_advice = "; use a larger --voxel-size",
  };
  absl::StatusOr<ReconstructionReport> report =
      RunReconstruction(params.options, {source, gate, sink, observer}, errors, cancel);
  if (!report.ok()) return report;
  if (absl::Status s = sink.Flush(); !s.ok()) return s;
  if (source.dropped() > 0) report->warnings.push_back(DroppedPointsNote(source.dropped()));
  return report;
}

}  // namespace membrane::client

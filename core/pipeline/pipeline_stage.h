// The stages of a reconstruction, in order, as progress reports and the statistics name them.
#ifndef MEMBRANE_CORE_PIPELINE_PIPELINE_STAGE_H_
#define MEMBRANE_CORE_PIPELINE_PIPELINE_STAGE_H_

namespace membrane {

// RunReconstruction runs them all; kDecode and kEncode are the work of its adapters (a file
// reader or an upload decoder, a mesh writer or encoder: cloud_source.h, mesh_sink.h).
// kDecimate runs only when a face budget is asked for (ReconstructionOptions::target_faces).
enum class PipelineStage {
  kDecode,
  kVoxelize,
  kShrink,
  kRelax,
  kSurface,
  kDecimate,
  kCheck,
  kEncode
};

// The stage's name as in the statistics JSON's "seconds" object: "decode", "voxelize", ...
const char* PipelineStageName(PipelineStage stage);

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_PIPELINE_STAGE_H_

// The stages of a reconstruction, in order, as progress reports and the statistics name them.
#ifndef MEMBRANE_CORE_PIPELINE_PIPELINE_STAGE_H_
#define MEMBRANE_CORE_PIPELINE_PIPELINE_STAGE_H_

namespace membrane {

// kDecode and kEncode belong to the caller (a file reader, an upload decoder, a mesh writer);
// ReconstructCloud runs the five stages between them.
enum class PipelineStage { kDecode, kVoxelize, kShrink, kRelax, kSurface, kCheck, kEncode };

// The stage's name as in the statistics JSON's "seconds" object: "decode", "voxelize", ...
const char* PipelineStageName(PipelineStage stage);

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_PIPELINE_STAGE_H_

#include "core/pipeline/pipeline_stage.h"

namespace membrane {

const char* PipelineStageName(PipelineStage stage) {
  switch (stage) {
    case PipelineStage::kDecode: return "decode";
    case PipelineStage::kVoxelize: return "voxelize";
    case PipelineStage::kShrink: return "shrink";
    case PipelineStage::kRelax: return "relax";
    case PipelineStage::kSurface: return "surface";
    case PipelineStage::kDecimate: return "decimate";
    case PipelineStage::kCheck: return "check";
    case PipelineStage::kEncode: return "encode";
  }
  return "unknown";
}

}  // namespace membrane

#include "core/synth/synthesize.h"

#include <memory>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "core/synth/cube_pinholes.h"
#include "core/synth/smooth_shape_cloud.h"
#include "core/synth/smooth_shapes.h"
#include "core/synth/synth_layout.h"

namespace membrane {

absl::StatusOr<PointCloud> SynthesizeShape(const SynthOptions& options) {
  if (!IsSynthShape(options.shape)) {
    return absl::InvalidArgumentError(absl::StrCat("shape '", options.shape,
                                                   "' is unknown: must be one of ",
                                                   absl::StrJoin(SynthShapeNames(), ", ")));
  }
  if (options.shape == kShapeCubePinholes) return SynthesizeCubePinholes(options);
  if (absl::Status s = ValidateSynthOptions(options); !s.ok()) return s;
  absl::StatusOr<std::unique_ptr<SurfaceSampler>> surface = MakeSmoothShape(options.shape);
  if (!surface.ok()) return surface.status();
  const SynthLayout layout = DrawSynthLayout(**surface, options);
  return SampleSmoothShape(**surface, layout, options);
}

}  // namespace membrane

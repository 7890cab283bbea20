#include "core/synth/synth_layout.h"

#include <memory>

#include "core/synth/smooth_shapes.h"
#include "core/synth/synth_random.h"

namespace membrane {

SynthLayout DrawSynthLayout(const SurfaceSampler& surface, const SynthOptions& options) {
  std::mt19937_64 rng = SeededStream(options.seed, kLayoutStream);
  SynthLayout layout;
  // The direction first: then it does not depend on the number of holes either.
  layout.density_direction = RandomUnitVector(rng);
  layout.hole_centres.reserve(static_cast<size_t>(options.holes));
  for (int i = 0; i < options.holes; ++i) layout.hole_centres.push_back(surface.Sample(rng).position);
  return layout;
}

absl::StatusOr<SynthLayout> SynthesizeLayout(const SynthOptions& options) {
  if (absl::Status s = ValidateSynthOptions(options); !s.ok()) return s;
  absl::StatusOr<std::unique_ptr<SurfaceSampler>> surface = MakeSmoothShape(options.shape);
  if (!surface.ok()) return surface.status();
  return DrawSynthLayout(**surface, options);
}

}  // namespace membrane

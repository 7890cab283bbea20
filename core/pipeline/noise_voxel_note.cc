#include "core/pipeline/noise_voxel_note.h"

#include "absl/strings/str_format.h"
#include "core/engine/point_noise.h"

namespace membrane {

std::optional<std::string> NoiseVoxelNote(const PlannedGrid& plan) {
  if (!VoxelRaisedForNoise(plan.formula_voxel_size, plan.voxel_size)) return std::nullopt;
  return absl::StrFormat(
      "the points scatter across their surface by %.3g (%.2g of formula (1)'s voxel %.3g): the "
      "voxel size is %.3g, %.3g times formula (1)'s, so that the membrane closes over the "
      "surface and not over its noise; a voxel size given explicitly is used as given",
      plan.noise.sigma, plan.noise.sigma / plan.formula_voxel_size, plan.formula_voxel_size,
      plan.voxel_size, plan.voxel_size / plan.formula_voxel_size);
}

}  // namespace membrane

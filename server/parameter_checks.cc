#include "server/parameter_checks.h"

#include <cmath>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/engine/plate_schedule.h"
#include "core/mesh/mesh_decimation.h"
#include "core/pipeline/grid_box.h"
#include "core/io/coordinate_shift.h"
#include "server/client_text.h"

namespace membrane::server {
namespace {

constexpr int kMaxInitialPlate = 100000;  // ValidateShrinkOptions' bound
constexpr int64_t kMaxTargetFaces = int64_t{1} << 31;  // faces are indexed by int32
constexpr int64_t kMaxVoxelBudget = 1'000'000'000'000;  // the client's --voxel-budget bound

absl::Status CheckRange(const char* field, int64_t value, int64_t low, int64_t high) {
  if (value >= low && value <= high) return absl::OkStatus();
  return absl::InvalidArgumentError(
      absl::StrFormat("%s %d is out of range [%d, %d]", field, value, low, high));
}

}  // namespace

absl::StatusOr<JobSettings> CheckParameters(const v1::Parameters& p, int64_t server_voxel_budget) {
  if (!std::isfinite(p.voxel_size()) || p.voxel_size() < 0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "voxel_size %g is out of range: positive (model units), or 0 for the default "
        "(formula (1), coarser for noisy points)",
        p.voxel_size()));
  }
  if (p.origin_size() != 0 && p.origin_size() != 3) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "origin has %d values; it must have none or 3 (x, y, z)", p.origin_size()));
  }
  for (double v : p.origin()) {
    if (!std::isfinite(v) || std::fabs(v) > kShiftUpTo) {
      return absl::InvalidArgumentError(absl::StrFormat(
          "origin value %g is out of range: finite, magnitude at most 2^40", v));
    }
  }
  for (const absl::Status& s :
       {CheckRange("initial_plate", p.initial_plate(), 0, kMaxInitialPlate),
        CheckRange("quantization", p.quantization(), 0, 30),
        CheckRange("compression_level", p.compression_level(), 0, 10),
        CheckRange("voxel_budget", p.voxel_budget(), 0,
                   server_voxel_budget > 0 ? server_voxel_budget : kMaxVoxelBudget),
        p.has_target_faces()
            ? CheckRange("target_faces", p.target_faces(), kMinTargetFaces, kMaxTargetFaces)
            : absl::OkStatus()}) {
    if (!s.ok()) return s;
  }
  JobSettings settings;
  for (int k = 0; k < p.origin_size(); ++k) settings.origin[k] = p.origin(k);
  ReconstructionOptions& r = settings.reconstruction;
  if (p.has_grid_box()) {
    const v1::GridBox& b = p.grid_box();
    const Box3d box = {{b.min_x(), b.min_y(), b.min_z()}, {b.max_x(), b.max_y(), b.max_z()}};
    // Whether it holds the points is known once they are decoded (PlanGrid).
    if (absl::Status s = CheckGridBox(box); !s.ok()) return s;
    r.grid_box = box;
  }
  if (p.has_voxel_plan()) {
    const v1::VoxelPlan& plan = p.voxel_plan();
    if (!(p.voxel_size() > 0)) {
      return absl::InvalidArgumentError(
          "voxel_plan needs the voxel_size it planned: voxel_size is 0 (the server's default)");
    }
    if (!std::isfinite(plan.formula_voxel_size()) || !(plan.formula_voxel_size() > 0)) {
      return absl::InvalidArgumentError(
          absl::StrFormat("voxel_plan formula_voxel_size %g is out of range: finite, > 0",
                          plan.formula_voxel_size()));
    }
    if (!std::isfinite(plan.point_noise()) || !(plan.point_noise() >= 0)) {
      return absl::InvalidArgumentError(absl::StrFormat(
          "voxel_plan point_noise %g is out of range: finite, >= 0", plan.point_noise()));
    }
    r.voxel_plan = VoxelPlanNote{plan.formula_voxel_size(), plan.point_noise()};
  }
  r.voxelize.voxel_size = p.voxel_size();
  r.voxelize.voxel_budget = p.voxel_budget() > 0 ? p.voxel_budget() : server_voxel_budget;
  r.shrink.initial_plate = p.initial_plate();
  if (!p.schedule().empty()) {
    absl::StatusOr<PlateSchedule> schedule = ParsePlateSchedule(p.schedule());
    if (!schedule.ok()) {
      return absl::InvalidArgumentError(
          absl::StrCat("schedule '", ClientText(p.schedule()), "' is not one of: halving, linear"));
    }
    r.shrink.schedule = *schedule;
  }
  if (!p.surface().empty()) {
    absl::StatusOr<SurfaceKind> surface = ParseSurfaceKind(p.surface());
    if (!surface.ok()) {
      return absl::InvalidArgumentError(
          absl::StrCat("surface '", ClientText(p.surface()), "' is not one of: smooth, cuberille"));
    }
    r.surface = *surface;
  }
  r.relax = !p.no_relax();
  if (p.has_target_faces()) r.target_faces = p.target_faces();
  // The mesh is built and checked on the grid of the encoding it is returned in.
  // Unset means the default encoding (DracoOptions'), as for `membrane reconstruct`.
  if (p.has_quantization()) settings.mesh_encoding.position_quantization_bits = p.quantization();
  if (p.has_compression_level()) settings.mesh_encoding.compression_level = p.compression_level();
  r.output_quantization_bits = settings.mesh_encoding.position_quantization_bits;
  r.output_bits_follow_voxel = !p.has_quantization();
  switch (p.mesh_format()) {
    case v1::MESH_FORMAT_UNSPECIFIED:
    case v1::MESH_FORMAT_DRACO:
      break;
    case v1::MESH_FORMAT_PLY:
      // PLY holds float32: the surface is built and checked on float32's grid.
      settings.ply_mesh = true;
      r.output_quantization_bits = 0;
      break;
    default:
      return absl::InvalidArgumentError(absl::StrCat(
          "mesh_format ", static_cast<int>(p.mesh_format()),
          " is not one of: 0 (unset: Draco), 1 (MESH_FORMAT_DRACO), 2 (MESH_FORMAT_PLY)"));
  }
  return settings;
}

}  // namespace membrane::server

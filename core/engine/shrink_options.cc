#include "core/engine/shrink_options.h"

#include <algorithm>

#include "absl/strings/str_format.h"

namespace membrane {

absl::Status ValidateShrinkOptions(const ShrinkOptions& o) {
  if (o.initial_plate < 0 || o.initial_plate > 100000) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "initial_plate %d is out of range [0, 100000] (0 = from the grid)", o.initial_plate));
  }
  if (o.chain.depth_bound < 0 || o.chain.depth_bound > 1000000) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "depth_bound %d is out of range [0, 1000000] (0 = unbounded)", o.chain.depth_bound));
  }
  if (o.threads < 1 || o.threads > 256) {
    return absl::InvalidArgumentError(
        absl::StrFormat("shrink threads %d is out of range [1, 256]", o.threads));
  }
  if (o.threads_min_voxels < 0) {
    return absl::InvalidArgumentError(
        absl::StrFormat("threads_min_voxels %d must be >= 0", o.threads_min_voxels));
  }
  if (!(o.local_snapshots.max_share >= 0 && o.local_snapshots.max_share <= 1000)) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "local_snapshots.max_share %g must be in [0, 1000] (0 = never)",
        o.local_snapshots.max_share));
  }
  if (o.local_snapshots.brick < 1) {
    return absl::InvalidArgumentError(
        absl::StrFormat("local_snapshots.brick %d must be >= 1", o.local_snapshots.brick));
  }
  if (o.local_snapshots.brick_plates < 0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "local_snapshots.brick_plates %d must be >= 0", o.local_snapshots.brick_plates));
  }
  if (o.closed_form_voxelwise_ratio < 0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "closed_form_voxelwise_ratio %d must be >= 0 (0 = always by planes)", o.closed_form_voxelwise_ratio));
  }
  if (o.interior_guard.factor < 2 || o.interior_guard.factor > 4) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "interior_guard.factor %d is out of range [2, 4]", o.interior_guard.factor));
  }
  if (o.coarse_plates.min_voxels < 0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "coarse_plates.min_voxels %d must be >= 0 (0 = never)", o.coarse_plates.min_voxels));
  }
  if (o.coarse_plates.factor < 2 || o.coarse_plates.factor > 4) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "coarse_plates.factor %d is out of range [2, 4]", o.coarse_plates.factor));
  }
  if (o.coarse_plates.min_plate < 8) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "coarse_plates.min_plate %d must be >= 8", o.coarse_plates.min_plate));
  }
  if (o.interior_guard.min_coarse_axis < 1) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "interior_guard.min_coarse_axis %d must be >= 1", o.interior_guard.min_coarse_axis));
  }
  if (o.closed_form_min_plate < 0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "closed_form_min_plate %d must be >= 0 (0 = never)", o.closed_form_min_plate));
  }
  if (o.guard.tunnel_min_plate < 1) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "guard_tunnel_min_plate %d must be >= 1", o.guard.tunnel_min_plate));
  }
  if (o.guard.short_loop_min_plate < 0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "guard_short_loop_min_plate %d must be >= 0 (0 = off)", o.guard.short_loop_min_plate));
  }
  if (o.guard.wall_notch_min_plate < 0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "guard_wall_notch_min_plate %d must be >= 0 (0 = off)", o.guard.wall_notch_min_plate));
  }
  if (o.guard.short_loop_steps < 1 || o.guard.short_loop_steps > 64) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "guard_short_loop_steps %d is out of range [1, 64]", o.guard.short_loop_steps));
  }
  if (o.guard.object_tunnel_plate < 0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "guard_object_tunnel_plate %d must be >= 0 (0 = none)", o.guard.object_tunnel_plate));
  }
  if (!(o.guard.dense_rim >= 0 && o.guard.dense_rim <= 8)) {
    return absl::InvalidArgumentError(
        absl::StrFormat("guard_dense_rim %g is out of range [0, 8]", o.guard.dense_rim));
  }
  if (o.tunnel_axis_ratio < 0) {
    return absl::InvalidArgumentError(
        absl::StrFormat("tunnel_axis_ratio %d must be >= 0 (0 = off)", o.tunnel_axis_ratio));
  }
  if (o.retry.tunnel_min_plate < 1) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "retry_tunnel_min_plate %d must be >= 1", o.retry.tunnel_min_plate));
  }
  if (o.retry.short_loop_min_plate < 0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "retry_short_loop_min_plate %d must be >= 0 (0 = off)", o.retry.short_loop_min_plate));
  }
  if (o.retry.wall_notch_min_plate < 0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "retry_wall_notch_min_plate %d must be >= 0 (0 = off)", o.retry.wall_notch_min_plate));
  }
  if (!(o.retry.max_hard_rim >= 0)) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "retry_max_hard_rim %g must be >= 0", o.retry.max_hard_rim));
  }
  if (o.chain.thick_wall_run < 1 || o.chain.thick_wall_run > 5) {
    return absl::InvalidArgumentError(
        absl::StrFormat("thick_wall_run %d is out of range [1, 5]", o.chain.thick_wall_run));
  }
  if (o.chain.thick_wall_detour < 0 || o.chain.thick_wall_detour > 16) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "thick_wall_detour %d is out of range [0, 16] (0 = off)", o.chain.thick_wall_detour));
  }
  if (!(o.chain.thin_part_min_spread >= 0 && o.chain.thin_part_min_spread <= 8)) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "thin_part_min_spread %g is out of range [0, 8] voxels (0 = not read)",
        o.chain.thin_part_min_spread));
  }
  if (!(o.chain.thin_wall_face_gap >= 0 && o.chain.thin_wall_face_gap <= 8) ||
      o.chain.thin_wall_face_min_plate < 1 || o.chain.thin_wall_face_max_run < 2 ||
      o.chain.thin_wall_face_max_run > 5) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "thin-wall face options out of range: thin_wall_face_gap %g [0, 8] voxels (0 = not "
        "read), thin_wall_face_min_plate %d [>= 1], thin_wall_face_max_run %d [2, 5]",
        o.chain.thin_wall_face_gap, o.chain.thin_wall_face_min_plate,
        o.chain.thin_wall_face_max_run));
  }
  const HoleOpeningOptions& h = o.holes;
  if (h.max_plug < 1 || h.max_plug > 32 || h.ring_radius < 2 || h.ring_radius > 16 ||
      h.join_radius < 1 || h.join_radius > 64 || h.min_data_rays < 1 || h.min_sectors < 0 ||
      h.min_sectors > 8 || h.max_openings < 0 || !(h.max_facing_cos > 0 && h.max_facing_cos <= 1) ||
      !(h.min_clearance >= 0 && h.min_clearance <= 4)) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "hole opening options out of range: max_plug %d [1, 32], ring_radius %d [2, 16], "
        "join_radius %d [1, 64], min_data_rays %d [>= 1], min_sectors %d [0, 8], "
        "max_openings %d [>= 0], max_facing_cos %g (0, 1], min_clearance %g [0, 4]",
        h.max_plug, h.ring_radius, h.join_radius, h.min_data_rays, h.min_sectors,
        h.max_openings, h.max_facing_cos, h.min_clearance));
  }
  return absl::OkStatus();
}

GuardSizes GridGuardSizes(const ShrinkOptions& o, const std::array<int, 3>& data_dims) {
  GuardSizes sizes = o.guard;
  if (o.tunnel_axis_ratio > 0) {
    sizes.object_tunnel_plate =
        std::max({data_dims[0], data_dims[1], data_dims[2]}) / o.tunnel_axis_ratio;
  }
  return sizes;
}

GuardSizes StrictGuardSizes(const ShrinkOptions& o, const GuardSizes& guard) {
  GuardSizes strict = guard;
  strict.tunnel_min_plate = std::max(guard.tunnel_min_plate, o.retry.tunnel_min_plate);
  // 0 turns a kind of tunnel off, in the guard or in the retry.
  auto stricter = [](int own, int retry) {
    return own > 0 && retry > 0 ? std::max(own, retry) : 0;
  };
  strict.short_loop_min_plate =
      stricter(guard.short_loop_min_plate, o.retry.short_loop_min_plate);
  strict.wall_notch_min_plate =
      stricter(guard.wall_notch_min_plate, o.retry.wall_notch_min_plate);
  return strict;
}

}  // namespace membrane

#include "core/engine/plate_schedule.h"

#include <algorithm>

#include "absl/status/status.h"
#include "core/engine/voxel_state.h"

namespace membrane {

absl::StatusOr<PlateSchedule> ParsePlateSchedule(const std::string& name) {
  if (name == "halving") return PlateSchedule::kHalving;
  if (name == "linear") return PlateSchedule::kLinear;
  return absl::InvalidArgumentError("schedule \"" + name + "\" is not one of: halving, linear");
}

std::string PlateScheduleName(PlateSchedule schedule) {
  return schedule == PlateSchedule::kHalving ? "halving" : "linear";
}

std::vector<int> PlateSizes(const std::array<int, 3>& data_dims, PlateSchedule schedule,
                            int initial_plate) {
  const int largest = std::max({data_dims[0], data_dims[1], data_dims[2], 1});
  std::vector<int> sizes;
  int n = largest;
  if (schedule == PlateSchedule::kHalving) {
    if (initial_plate > 0) {
      n = initial_plate;
      sizes.push_back(n);
    }
    while (n > 1) {
      n = (n + 1) / 2;
      sizes.push_back(n);
    }
    if (sizes.empty()) sizes.push_back(1);
  } else {
    for (n = initial_plate > 0 ? initial_plate : largest; n >= 1; --n) sizes.push_back(n);
  }
  return sizes;
}

std::vector<int> GenerationLabels(int generations) {
  std::vector<int> labels(static_cast<size_t>(generations));
  const int shift = std::max(0, generations - kMaxGenerationLabel);
  for (int i = 0; i < generations; ++i) labels[static_cast<size_t>(i)] = std::max(1, i + 1 - shift);
  return labels;
}

}  // namespace membrane

// Plate sizes of successive generations (paper Algorithm 1; algorithm-notes 2).
#ifndef MEMBRANE_CORE_ENGINE_PLATE_SCHEDULE_H_
#define MEMBRANE_CORE_ENGINE_PLATE_SCHEDULE_H_

#include <array>
#include <string>
#include <vector>

#include "absl/status/statusor.h"

namespace membrane {

enum class PlateSchedule {
  kHalving,  // Algorithm 1: n = max(nx, ny, nz), then n = (n + 1) div 2 before each generation
  kLinear,   // the paper's "best solution": n decreases by 1 down to 1
};

// Parses "halving" or "linear"; InvalidArgument naming the allowed values otherwise.
absl::StatusOr<PlateSchedule> ParsePlateSchedule(const std::string& name);
std::string PlateScheduleName(PlateSchedule schedule);

// The plate size of every generation, first to last (the last is 1), for a data region of
// `data_dims` voxels. `initial_plate` > 0 replaces the first size; halving then continues
// from it, linear counts down from it.
std::vector<int> PlateSizes(const std::array<int, 3>& data_dims, PlateSchedule schedule,
                            int initial_plate);

// Generation labels for `generations` generations (1-based in the output order): labels fit
// in 7 bits, so when there are more than 127 generations the first (largest-plate) ones share
// label 1 and the last 126 keep distinct labels, where the incursion test needs them.
std::vector<int> GenerationLabels(int generations);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_PLATE_SCHEDULE_H_

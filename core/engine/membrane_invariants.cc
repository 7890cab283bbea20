#include "core/engine/membrane_invariants.h"

#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/engine/voxel_topology.h"

namespace membrane {
namespace {

struct Violation {
  int64_t count = 0;
  int64_t example = -1;
  void Add(int64_t i) {
    if (count++ == 0) example = i;
  }
};

void Report(const VoxelGrid& grid, const char* what, const Violation& v, std::string& out) {
  if (v.count == 0) return;
  const Coord c = grid.CoordOf(v.example);
  absl::StrAppendFormat(&out, "%s%s: %d voxels (e.g. %d,%d,%d)", out.empty() ? "" : "; ", what,
                        v.count, c.x, c.y, c.z);
}

}  // namespace

absl::Status CheckMembraneInvariants(const VoxelGrid& grid, const InvariantOptions& options) {
  const auto& d = grid.dims();
  const auto st = grid.strides();
  const std::array<int64_t, 27>& offsets = grid.block_offsets();
  const VoxelState* s = grid.states().data();
  Violation hard_outside, hard_lost, inside_touches, soft_exposed, border_not_outside;
  int64_t hard = 0;
  for (int z = 0; z < d[2]; ++z)
    for (int y = 0; y < d[1]; ++y)
      for (int x = 0; x < d[0]; ++x) {
        const int64_t i = grid.Index(x, y, z);
        const VoxelState v = s[i];
        if (IsOutside(v)) {
          if (HardnessOf(v) != Hardness::kSoft) hard_outside.Add(i);
          continue;
        }
        if (IsHard(v)) ++hard;
        if (x == 0 || y == 0 || z == 0 || x == d[0] - 1 || y == d[1] - 1 || z == d[2] - 1) {
          border_not_outside.Add(i);
          continue;
        }
        bool face_out = false, any_out = false;
        for (int k = 0; k < 27; ++k) {
          if (!IsOutside(s[i + offsets[k]])) continue;
          any_out = true;
          if (IsFaceStep(k)) face_out = true;
        }
        if (IsInside(v) && any_out) inside_touches.Add(i);
        if (options.require_property3 && IsBoundary(v) && face_out && v == kBoundarySoft) {
          soft_exposed.Add(i);
        }
      }
  if (options.expected_hard_voxels >= 0 && hard != options.expected_hard_voxels) {
    hard_lost.count = options.expected_hard_voxels - hard;
    hard_lost.example = 0;
  }

  // One 6-connected membrane per shell.
  std::vector<int32_t> shell;
  const int shells = LabelShells(grid, shell);
  std::vector<int> membranes(static_cast<size_t>(shells), 0);
  std::vector<uint8_t> seen(static_cast<size_t>(grid.size()), 0);
  std::vector<int64_t> stack;
  const int64_t steps[6] = {-st[0], st[0], -st[1], st[1], -st[2], st[2]};
  Violation split_membrane;
  for (int64_t i = 0; i < grid.size(); ++i) {
    if (!IsBoundary(s[i]) || seen[static_cast<size_t>(i)]) continue;
    if (++membranes[static_cast<size_t>(shell[static_cast<size_t>(i)])] == 2) split_membrane.Add(i);
    seen[static_cast<size_t>(i)] = 1;
    stack.push_back(i);
    while (!stack.empty()) {
      const int64_t v = stack.back();
      stack.pop_back();
      for (int64_t step : steps) {
        const int64_t w = v + step;
        if (w < 0 || w >= grid.size() || seen[static_cast<size_t>(w)] || !IsBoundary(s[w])) continue;
        seen[static_cast<size_t>(w)] = 1;
        stack.push_back(w);
      }
    }
  }
  const VoxelTopology topo = ComputeVoxelTopology(grid);
  Violation cavities;
  cavities.count = topo.cavities;
  cavities.example = 0;

  std::string out;
  Report(grid, "Property 4: hard outside voxels", hard_outside, out);
  Report(grid, "Property 4: hard voxels lost", hard_lost, out);
  Report(grid, "voxels on the array border not outside", border_not_outside, out);
  Report(grid, "Property 2: inside voxels 26-adjacent to outside", inside_touches, out);
  Report(grid, "Property 3: soft boundary voxels 6-adjacent to outside", soft_exposed, out);
  Report(grid, "shells whose membrane is not 6-connected", split_membrane, out);
  Report(grid, "outside cavities", cavities, out);
  if (out.empty()) return absl::OkStatus();
  return absl::FailedPreconditionError(absl::StrCat("membrane invariants violated: ", out));
}

}  // namespace membrane

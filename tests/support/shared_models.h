// The models of ../shared/data/clouds and the topology a correct reconstruction of each has
// (its README; the second batch's cloud JSONs hold the same values as `expected`).
#ifndef MEMBRANE_TESTS_SUPPORT_SHARED_MODELS_H_
#define MEMBRANE_TESTS_SUPPORT_SHARED_MODELS_H_

#include <string>
#include <vector>

#include "core/synth/shape_catalog.h"

namespace membrane::testing {

struct SharedModel {
  std::string model;               // e.g. "horse"; clouds are <model>-<kind>.ply
  std::vector<std::string> kinds;  // "scan", "variable"
  ShapeTopology expected;          // shells and genus sorted ascending
  bool genus_asserted = true;      // false for the teapot (its openings make it ambiguous)
};

// Every shared model, the first batch (bunny, rocker arm, fandisk, spot, teapot) first.
const std::vector<SharedModel>& SharedModels();

// True when `shells` and the per-shell `genus` (any order) are what `m` expects.
bool HasExpectedTopology(const SharedModel& m, int shells, std::vector<int> genus);

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_SUPPORT_SHARED_MODELS_H_

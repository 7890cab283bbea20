#include "tests/support/shared_models.h"

#include <algorithm>

namespace membrane::testing {

const std::vector<SharedModel>& SharedModels() {
  static const std::vector<SharedModel> models = {
      {"stanford-bunny", {"scan", "variable"}, {1, {0}}, true},
      {"rocker-arm", {"scan", "variable"}, {1, {1}}, true},
      {"fandisk", {"scan", "variable"}, {1, {0}}, true},
      {"spot", {"scan", "variable"}, {1, {0}}, true},
      {"teapot", {"scan", "variable"}, {1, {}}, false},
      {"horse", {"scan", "variable"}, {1, {0}}, true},
      {"cow", {"scan", "variable"}, {1, {0}}, true},
      {"beast", {"scan", "variable"}, {1, {0}}, true},
      {"ogre-belt", {"scan"}, {1, {1}}, true},
      {"cow-spot-belt", {"scan"}, {3, {0, 0, 1}}, true},
      {"pierced-disk", {"scan"}, {1, {1}}, true},
  };
  return models;
}

bool HasExpectedTopology(const SharedModel& m, int shells, std::vector<int> genus) {
  if (shells != m.expected.shells) return false;
  if (!m.genus_asserted) return true;
  std::sort(genus.begin(), genus.end());
  return genus == m.expected.genus;
}

}  // namespace membrane::testing

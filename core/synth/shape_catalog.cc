#include "core/synth/shape_catalog.h"

namespace membrane {

std::vector<std::string> SynthShapeNames() {
  return {std::string(kShapeSphere), std::string(kShapeTwoSpheres), std::string(kShapeTorus),
          std::string(kShapeCappedSphere), std::string(kShapeCubePinholes)};
}

bool IsSynthShape(std::string_view shape) {
  for (const std::string& name : SynthShapeNames())
    if (name == shape) return true;
  return false;
}

ShapeTopology ExpectedTopology(const std::string& shape) {
  if (shape == kShapeTwoSpheres) return {2, {0, 0}};
  if (shape == kShapeTorus) return {1, {1}};
  if (shape == kShapeSphere || shape == kShapeCappedSphere || shape == kShapeCubePinholes) {
    return {1, {0}};
  }
  return {0, {}};
}

}  // namespace membrane

// The names of the synthetic shapes and their true topology.
#ifndef MEMBRANE_CORE_SYNTH_SHAPE_CATALOG_H_
#define MEMBRANE_CORE_SYNTH_SHAPE_CATALOG_H_

#include <string>
#include <string_view>
#include <vector>

namespace membrane {

inline constexpr std::string_view kShapeSphere = "sphere";
inline constexpr std::string_view kShapeTwoSpheres = "two-spheres";
inline constexpr std::string_view kShapeTorus = "torus";
inline constexpr std::string_view kShapeCappedSphere = "capped-sphere";
inline constexpr std::string_view kShapeCubePinholes = "cube-pinholes";

// Every shape SynthesizeShape accepts, in a fixed order (the order of help texts).
std::vector<std::string> SynthShapeNames();

// True for a name in SynthShapeNames().
bool IsSynthShape(std::string_view shape);

// The closed surfaces a correct reconstruction must produce: `shells` connected components and
// the genus of each (sorted ascending). Holes, noise and density variation of the cloud do not
// change it: they are defects the reconstruction must bridge.
struct ShapeTopology {
  int shells = 0;
  std::vector<int> genus;
};

// Topology of `shape`: sphere 1/[0], two-spheres 2/[0,0], torus 1/[1], capped-sphere 1/[0],
// cube-pinholes 1/[0] (the pinholes are meant to be closed). {0, {}} for an unknown name.
ShapeTopology ExpectedTopology(const std::string& shape);

}  // namespace membrane

#endif  // MEMBRANE_CORE_SYNTH_SHAPE_CATALOG_H_

// A picture of a triangle mesh from three sides, drawn on the CPU: the preview membraned keeps
// with each result (shown in the web console's job list) and `membrane render`'s output.
#ifndef MEMBRANE_CORE_RENDER_MESH_VIEWS_H_
#define MEMBRANE_CORE_RENDER_MESH_VIEWS_H_

#include <array>
#include <cstdint>

#include "core/geometry/triangle_mesh.h"
#include "core/render/png_codec.h"

namespace membrane {

// The colours of shells 0, 1, ... (cycled), those of the web console's 3D view.
inline constexpr std::array<uint32_t, 8> kShellColours = {
    0x6fa8dc, 0xe69138, 0x93c47d, 0xc27ba0, 0xf1c232, 0x76a5af, 0xe06666, 0x8e7cc3};

struct MeshViewOptions {
  int view_pixels = 256;          // each view is a square this wide, [16, 4096]
  uint32_t background = 0x20262f; // 0xRRGGBB
};

// Three orthographic views of `mesh` side by side, each view_pixels square: from the front
// (looking along +y; x right, z up), from the side (along -x; y right, z up) and from above
// (along -z; x right, y up). One scale for all three: the bounding box's largest side fills
// 90% of a view. Each shell (connected set of faces) in its colour of kShellColours, shaded
// by a light from the viewer's upper left; the nearest face wins each pixel (a depth buffer).
// Faces with indices out of range or no area are skipped; an empty mesh gives the background.
// Cost: about one pass over the faces per view, plus the pixels each face covers.
RgbImage RenderMeshViews(const TriangleMesh& mesh, const MeshViewOptions& options = {});

}  // namespace membrane

#endif  // MEMBRANE_CORE_RENDER_MESH_VIEWS_H_

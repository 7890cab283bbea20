#include "core/render/mesh_views.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

namespace membrane {
namespace {

using V3 = std::array<double, 3>;

double Dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V3 Sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 Cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
V3 ToV3(const Point3f& p) { return {p[0], p[1], p[2]}; }

// A view: the screen's right and up, and the direction toward the viewer (right x up).
struct View {
  V3 right, up, toward;
};
constexpr View kViews[3] = {
    {{1, 0, 0}, {0, 0, 1}, {0, -1, 0}},  // front
    {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}},   // side
    {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}},   // above
};

// The shell of each face: connected components of faces sharing a vertex.
std::vector<int> FaceShells(const TriangleMesh& mesh, const std::vector<bool>& valid) {
  std::vector<int32_t> parent(mesh.vertices.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    if (!valid[f]) continue;
    const int32_t a = find(mesh.faces[f][0]);
    for (int k = 1; k < 3; ++k) {
      const int32_t b = find(mesh.faces[f][k]);
      if (a != b) parent[b] = a;
    }
  }
  std::vector<int> label(mesh.vertices.size(), -1);
  std::vector<int> shells(mesh.faces.size(), 0);
  int count = 0;
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    if (!valid[f]) continue;
    int& l = label[find(mesh.faces[f][0])];
    if (l < 0) l = count++;
    shells[f] = l;
  }
  return shells;
}

uint32_t Shade(uint32_t rgb, double intensity) {
  uint32_t out = 0;
  for (int shift = 16; shift >= 0; shift -= 8) {
    const double c = ((rgb >> shift) & 0xff) * intensity;
    out |= uint32_t(std::clamp(std::lround(c), 0L, 255L)) << shift;
  }
  return out;
}

}  // namespace

RgbImage RenderMeshViews(const TriangleMesh& mesh, const MeshViewOptions& options) {
  const int n = std::clamp(options.view_pixels, 16, 4096);
  RgbImage image(3 * n, n, options.background);
  const int32_t vertex_count = static_cast<int32_t>(mesh.vertices.size());
  std::vector<bool> valid(mesh.faces.size());
  V3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
        std::numeric_limits<double>::infinity()};
  V3 hi{-lo[0], -lo[1], -lo[2]};
  bool any = false;
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& face = mesh.faces[f];
    valid[f] = std::all_of(face.begin(), face.end(),
                           [&](int32_t v) { return v >= 0 && v < vertex_count; });
    if (!valid[f]) continue;
    for (const int32_t v : face) {
      const V3 p = ToV3(mesh.vertices[v]);
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) valid[f] = false;
    }
    if (!valid[f]) continue;
    for (const int32_t v : face) {
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min<double>(lo[a], mesh.vertices[v][a]);
        hi[a] = std::max<double>(hi[a], mesh.vertices[v][a]);
      }
    }
    any = true;
  }
  if (!any) return image;
  const V3 centre{(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
  const double side = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-30});
  const double scale = 0.9 * n / side;
  const std::vector<int> shells = FaceShells(mesh, valid);

  std::vector<float> depth(size_t(n) * n);
  for (int v = 0; v < 3; ++v) {
    const View& view = kViews[v];
    // The light comes from the viewer's upper left.
    V3 light{view.toward[0] + 0.5 * view.up[0] - 0.4 * view.right[0],
             view.toward[1] + 0.5 * view.up[1] - 0.4 * view.right[1],
             view.toward[2] + 0.5 * view.up[2] - 0.4 * view.right[2]};
    const double light_norm = std::sqrt(Dot(light, light));
    for (double& c : light) c /= light_norm;
    std::fill(depth.begin(), depth.end(), -std::numeric_limits<float>::infinity());
    for (size_t f = 0; f < mesh.faces.size(); ++f) {
      if (!valid[f]) continue;
      double sx[3], sy[3], sz[3];
      V3 p[3];
      for (int k = 0; k < 3; ++k) {
        p[k] = Sub(ToV3(mesh.vertices[mesh.faces[f][k]]), centre);
        sx[k] = n / 2.0 + scale * Dot(p[k], view.right);
        sy[k] = n / 2.0 - scale * Dot(p[k], view.up);
        sz[k] = Dot(p[k], view.toward);
      }
      // The pixels whose centre (x + 0.5, y + 0.5) lies in the face's box. Most faces of a big
      // mesh hold none: they are skipped before their normal and shade are computed.
      const int x0 =
          std::max(0, static_cast<int>(std::ceil(std::min({sx[0], sx[1], sx[2]}) - 0.5)));
      const int x1 =
          std::min(n - 1, static_cast<int>(std::floor(std::max({sx[0], sx[1], sx[2]}) - 0.5)));
      if (x0 > x1) continue;
      const int y0 =
          std::max(0, static_cast<int>(std::ceil(std::min({sy[0], sy[1], sy[2]}) - 0.5)));
      const int y1 =
          std::min(n - 1, static_cast<int>(std::floor(std::max({sy[0], sy[1], sy[2]}) - 0.5)));
      if (y0 > y1) continue;
      const double area = (sx[1] - sx[0]) * (sy[2] - sy[0]) - (sx[2] - sx[0]) * (sy[1] - sy[0]);
      if (area == 0) continue;
      V3 normal = Cross(Sub(p[1], p[0]), Sub(p[2], p[0]));
      const double length = std::sqrt(Dot(normal, normal));
      if (!(length > 0)) continue;
      // Both sides lit alike: an open mesh shows its inside as a closed one its outside.
      const double lambert = std::abs(Dot(normal, light)) / length;
      const uint32_t colour =
          Shade(kShellColours[shells[f] % kShellColours.size()], 0.3 + 0.7 * lambert);
      for (int y = y0; y <= y1; ++y) {
        const double py = y + 0.5;
        for (int x = x0; x <= x1; ++x) {
          const double px = x + 0.5;
          // Barycentric weights of the pixel's centre, positive inside whatever the winding.
          const double w0 = ((sx[1] - px) * (sy[2] - py) - (sx[2] - px) * (sy[1] - py)) / area;
          const double w1 = ((sx[2] - px) * (sy[0] - py) - (sx[0] - px) * (sy[2] - py)) / area;
          const double w2 = 1 - w0 - w1;
          if (w0 < 0 || w1 < 0 || w2 < 0) continue;
          const float z = static_cast<float>(w0 * sz[0] + w1 * sz[1] + w2 * sz[2]);
          float& d = depth[size_t(y) * n + x];
          if (z <= d) continue;
          d = z;
          uint8_t* out = &image.pixels[(size_t(y) * image.width + v * n + x) * 3];
          out[0] = uint8_t(colour >> 16);
          out[1] = uint8_t(colour >> 8);
          out[2] = uint8_t(colour);
        }
      }
    }
  }
  return image;
}

}  // namespace membrane

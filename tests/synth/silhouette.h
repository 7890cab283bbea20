// Test helper: the silhouette of points seen along a direction, as occupied pixels.
#ifndef MEMBRANE_TESTS_SYNTH_SILHOUETTE_H_
#define MEMBRANE_TESTS_SYNTH_SILHOUETTE_H_

#include <vector>

#include "core/geometry/point_cloud.h"
#include "core/geometry/vec3.h"

namespace membrane::testing {

// Pixels of side `pixel` covering [-half_width, half_width]^2 of the plane orthogonal to a
// unit `direction`, through the origin.
class Silhouette {
 public:
  Silhouette(const Vec3d& direction, double half_width, double pixel);

  // Marks the pixel under `p`; points projecting outside the window are ignored.
  void Add(const Point3f& p);
  void AddAll(const PointCloud& cloud) {
    for (const Point3f& p : cloud.points) Add(p);
  }

  // Empty pixels not 4-connected to the window's border through empty pixels: the holes a
  // viewer would see through the silhouette.
  int EnclosedEmptyPixels() const;
  // True when some pixel is occupied in both silhouettes (same direction and window).
  bool Overlaps(const Silhouette& other) const;

 private:
  Vec3d u_, v_;  // orthonormal basis of the image plane
  double half_width_, pixel_;
  int n_;  // pixels per side
  std::vector<char> occupied_;
};

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_SYNTH_SILHOUETTE_H_

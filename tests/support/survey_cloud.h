// Georeferenced copies of the synthetic clouds: the tests of coordinates that the readers move
// near 0 (core/io/coordinate_shift.h), for the client and the service alike.
#ifndef MEMBRANE_TESTS_SUPPORT_SURVEY_CLOUD_H_
#define MEMBRANE_TESTS_SUPPORT_SURVEY_CLOUD_H_

#include <array>
#include <string>

#include "core/geometry/point_cloud.h"
#include "core/geometry/triangle_mesh.h"

namespace membrane::testing {

// A UTM easting and northing and a height: float32 there lies 0.03 and 0.25 m apart, as coarse
// as a synthetic cloud's whole voxel grid, so without the move the cloud is refused.
inline constexpr Origin3d kSurveyOffset = {512345.678, 4123456.789, 102.5};

// Writes the cloud in `in` to `out` (.xyz text, in double) moved by kSurveyOffset, as a
// georeferenced scan would hold it. Fails the test on error.
void WriteSurveyCopy(const std::string& in, const std::string& out);

// The centre of the bounding box of `mesh`'s vertices in its file's coordinates (vertex +
// origin).
std::array<double, 3> FileBoxCentre(const TriangleMesh& mesh);

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_SUPPORT_SURVEY_CLOUD_H_

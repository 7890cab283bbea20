// The uploads of the server tests: a synthetic shape's points as a lossless Draco cloud.
#ifndef MEMBRANE_TESTS_SERVER_DRACO_UPLOAD_H_
#define MEMBRANE_TESTS_SERVER_DRACO_UPLOAD_H_

#include <string>

namespace membrane::testing {

// A Draco point cloud (lossless) of `points` points of the synthetic `shape` ("sphere",
// "torus", ...); a test failure and possibly empty bytes when synthesis or encoding fails.
std::string LosslessDracoCloud(const std::string& shape, int points);

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_SERVER_DRACO_UPLOAD_H_

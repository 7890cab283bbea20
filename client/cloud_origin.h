// What the client says and checks about a cloud its reader moved near 0 (core/io/
// coordinate_shift.h): the mesh comes back in the moved positions, and only an output format
// that holds doubles can put it back where the input was.
#ifndef MEMBRANE_CLIENT_CLOUD_ORIGIN_H_
#define MEMBRANE_CLIENT_CLOUD_ORIGIN_H_

#include <string>

#include "absl/status/status.h"
#include "core/geometry/point_cloud.h"

namespace membrane::client {

// OK unless `origin` is not zero and the mesh file `output` would hold float32 positions only
// (.stl, .drc): then InvalidArgument "OUTPUT: ..." (CheckOriginFitsFormat), said before any
// work. OK as well for an output without a mesh extension (FormatFromPath reports that).
absl::Status CheckOutputKeepsOrigin(const Origin3d& origin, const std::string& output);

// "" for a zero origin; otherwise " (moved by -X, -Y, -Z for float32)", for the decode line.
std::string OriginNote(const Origin3d& origin);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_CLOUD_ORIGIN_H_

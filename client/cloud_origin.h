// What the client says and checks about a cloud its reader moved near 0 (core/io/
// coordinate_shift.h): the mesh comes back in the moved positions, and only an output format
// that holds doubles can put it back where the input was.
#ifndef MEMBRANE_CLIENT_CLOUD_ORIGIN_H_
#define MEMBRANE_CLIENT_CLOUD_ORIGIN_H_

#include <string>

#include "absl/status/status.h"
#include "core/geometry/point_cloud.h"
#include "core/io/file_format.h"

namespace membrane::client {

// OK unless `origin` is not zero and a mesh file of `format` would hold float32 positions
// only (.stl, .drc): then InvalidArgument "OUTPUT_NAME: ..." (CheckOriginFitsFormat), said
// before any work.
absl::Status CheckOutputKeepsOrigin(const Origin3d& origin, FileFormat format,
                                    const std::string& output_name);

// "" for a zero origin; otherwise " (moved by -X, -Y, -Z for float32)", for the decode line.
std::string OriginNote(const Origin3d& origin);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_CLOUD_ORIGIN_H_

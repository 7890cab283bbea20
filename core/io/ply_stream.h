// Reading a binary PLY point cloud from its file in pieces, so that the file's bytes and the
// decoded points are never both in memory: a 50M-point scan is 600 MB of float32 positions,
// and the file holding them at least as much again.
#ifndef MEMBRANE_CORE_IO_PLY_STREAM_H_
#define MEMBRANE_CORE_IO_PLY_STREAM_H_

#include <cstddef>
#include <optional>
#include <string>

#include "core/geometry/point_cloud.h"

namespace membrane {

// The bytes read at a time: whole rows of about this size.
inline constexpr size_t kPlyStreamChunkBytes = size_t{4} << 20;

// The cloud of the binary PLY file at `path` (ReadPlyPointCloud's x, y, z and origin), read
// through one buffer of about kPlyStreamChunkBytes: the header from the file's first bytes,
// then the vertex element's rows piece by piece into the points. Only a file whose elements
// all have fixed-size rows (no lists), whose "vertex" element has scalar x, y and z, and which
// holds every row its header declares is read so; nullopt for any other file and for any
// problem reading it (ASCII, lists, truncated, a header past the first 64 KB, unreadable,
// shrunk while read). The caller then reads the file whole, which gives the same cloud or the
// error that names the problem. Coordinates are not checked for finiteness here.
std::optional<PointCloud> StreamPlyPointCloud(const std::string& path);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_PLY_STREAM_H_

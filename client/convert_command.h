// `membrane convert INPUT OUTPUT`: point clouds and meshes between the supported formats.
#ifndef MEMBRANE_CLIENT_CONVERT_COMMAND_H_
#define MEMBRANE_CLIENT_CONVERT_COMMAND_H_

#include "client/command.h"

namespace CLI {
class App;
}  // namespace CLI

namespace membrane::client {

// Adds the `convert` subcommand to `parent`. Its action reads INPUT by extension and writes
// OUTPUT by extension: a mesh (an input with faces) to a mesh format keeps its faces; to a
// point-cloud-only format (.xyz) it writes the vertices; a point cloud (an input without
// faces, or .xyz/.pcd) goes to a point cloud format. Draco output uses Draco's default
// quantization (11 bits). Prints one line on stdout. Statuses: InvalidArgument for an
// unsupported extension (checked before reading), unreadable or malformed input, or a point
// cloud asked to become an STL; the reader's NotFound for a missing file.
Command AddConvertCommand(CLI::App& parent);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_CONVERT_COMMAND_H_

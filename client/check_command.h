// `membrane check MESH [--json]`: is a mesh closed, manifold and oriented, and its topology.
#ifndef MEMBRANE_CLIENT_CHECK_COMMAND_H_
#define MEMBRANE_CLIENT_CHECK_COMMAND_H_

#include "client/command.h"

namespace CLI {
class App;
}  // namespace CLI

namespace membrane::client {

// Adds the `check` subcommand to `parent`. Its action reads MESH (.ply .obj .stl .drc), runs
// CheckMesh and prints on stdout either "key: value" lines (vertices, faces, closed, manifold,
// oriented, shells, genus, self-intersections, ...) or, with --json, MeshReportToJson.
// Statuses: OK when the mesh is closed, manifold and oriented; FailedPrecondition (exit 5)
// naming each failed property otherwise, after printing the report; the reader's status for
// unreadable input, and InvalidArgument for a file without faces.
Command AddCheckCommand(CLI::App& parent);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_CHECK_COMMAND_H_

// `membrane render MESH -o preview.png [--size N]`: a PNG picture of a mesh from three sides,
// as membraned keeps with each result for the web console (core/render/mesh_views.h).
#ifndef MEMBRANE_CLIENT_RENDER_COMMAND_H_
#define MEMBRANE_CLIENT_RENDER_COMMAND_H_

#include "client/command.h"

namespace CLI {
class App;
}  // namespace CLI

namespace membrane::client {

// Adds the `render` subcommand to `parent`. Its action reads MESH (.ply .obj .off .stl .drc),
// draws RenderMeshViews with views of --size pixels (16..4096, default 256) and writes the
// PNG to -o, which must end in .png. Statuses: InvalidArgument (exit 3) for another output
// extension, a file without faces, or the reader's and the writer's errors.
Command AddRenderCommand(CLI::App& parent);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_RENDER_COMMAND_H_

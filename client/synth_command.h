// `membrane synth SHAPE -o OUTPUT [...]`: a synthetic point cloud with a known topology.
#ifndef MEMBRANE_CLIENT_SYNTH_COMMAND_H_
#define MEMBRANE_CLIENT_SYNTH_COMMAND_H_

#include "client/command.h"

namespace CLI {
class App;
}  // namespace CLI

namespace membrane::client {

// Adds the `synth` subcommand to `parent`. Its action checks every value against the ranges of
// core/synth/synth_options.h (InvalidArgument naming the flag), generates the cloud with
// SynthesizeShape and writes it by the output's extension (.ply binary, .xyz, .obj, .drc),
// then prints one line on stdout. Statuses: InvalidArgument for an unknown shape, a value out
// of range, an unsupported extension or an unwritable path; those of SynthesizeShape.
Command AddSynthCommand(CLI::App& parent);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_SYNTH_COMMAND_H_

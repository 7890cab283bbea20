// The human-readable report printed on stdout after a reconstruction: the paper's table
// (Tables 1 to 4) and a summary line.
#ifndef MEMBRANE_CLIENT_REPORT_TEXT_H_
#define MEMBRANE_CLIENT_REPORT_TEXT_H_

#include <string>
#include <vector>

#include "client/remote_reconstruction.h"
#include "core/pipeline/reconstruction_report.h"
#include "core/engine/membrane_shrinker.h"

namespace membrane::client {

// One header row and one row per generation, columns right-aligned:
//   plate size | soft voxels | started contractions | backtrackings | seconds
// Rows of a kept handle retry end with " *", and a line under the table says what that means.
// Each line ends with '\n'.
std::string GenerationTable(const std::vector<GenerationStats>& generations);

// One line (ending with '\n'): grid, points, hard voxels, density ratio, mesh shells and
// genus, closed/manifold, then seconds per stage, e.g.
//   "grid 164x104x82, 35910 points, 19144 hard voxels, density ratio 0.87; mesh 1 shell,
//    genus [0], closed, manifold; seconds: decode 0.01 voxelize 0.02 ... total 1.2"
// (one line in reality; wrapped here).
std::string SummaryLine(const ReconstructionReport& report);

// The summary line of a --server run (ending with '\n'): job id, mesh shells, genus,
// closed/manifold, and the bytes on the wire, e.g.
//   "job 9f2c...: mesh 1 shell, genus [1], closed, manifold, 20000 faces; upload 310000 bytes
//    (25.8% of raw float32), download 150000 bytes"
std::string RemoteSummaryLine(const RemoteOutcome& outcome);

// One "warning: <text>\n" line per warning of the report (ReconstructionReport::warnings, or
// the server's), for stderr after the summary: they say what the result may get wrong, so
// --quiet, which silences progress, does not silence them. Empty for none.
std::string WarningLines(const std::vector<std::string>& warnings);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_REPORT_TEXT_H_

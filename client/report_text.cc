#include "client/report_text.h"

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"

namespace membrane::client {

std::string GenerationTable(const std::vector<GenerationStats>& generations) {
  std::string table = "plate size | soft voxels | started contractions | backtrackings | seconds\n";
  bool retried = false;
  for (const GenerationStats& g : generations) {
    absl::StrAppendFormat(&table, "%10d | %11d | %20d | %13d | %7.3f%s\n", g.plate_size,
                          g.soft_voxels, g.started_contractions, g.backtrackings, g.seconds,
                          g.handle_retry ? " *" : "");
    retried = retried || g.handle_retry;
  }
  if (retried) table += "* run again by the handle retry, whose result has fewer handles\n";
  return table;
}

std::string SummaryLine(const ReconstructionReport& r) {
  const MeshReport& m = r.mesh;
  const StageSeconds& s = r.seconds;
  std::string decimated, decimate_seconds;
  if (r.decimation.ran) {
    const DecimationStats& d = r.decimation.stats;
    decimated = absl::StrFormat(
        "; decimated %d -> %d faces (target %d), moved by at most %.3g (mean %.3g)",
        d.faces_before, d.faces_after, d.target_faces, r.decimation.error.max,
        r.decimation.error.mean);
    decimate_seconds = absl::StrFormat(" decimate %.3f", s.decimate);
  }
  return absl::StrFormat(
      "grid %s, %d points, %d hard voxels, density ratio %.3g; mesh %d shell%s, genus [%s], "
      "%s, %s%s; seconds: decode %.3f voxelize %.3f shrink %.3f relax %.3f surface %.3f%s "
      "check %.3f encode %.3f total %.3f\n",
      absl::StrJoin(r.grid, "x"), r.points, r.hard_voxels, r.density_ratio, m.shells,
      m.shells == 1 ? "" : "s", absl::StrJoin(m.genus, ", "), m.closed ? "closed" : "NOT closed",
      m.manifold ? "manifold" : "NOT manifold", decimated, s.decode, s.voxelize, s.shrink,
      s.relax, s.surface, decimate_seconds, s.check, s.encode, s.total);
}

std::string RemoteSummaryLine(const RemoteOutcome& o) {
  const MeshReport& m = o.mesh;
  return absl::StrFormat(
      "job %s: mesh %d shell%s, genus [%s], %s, %s, %d faces; upload %d bytes (%.1f%% of raw "
      "float32), download %d bytes\n",
      o.job_id, m.shells, m.shells == 1 ? "" : "s", absl::StrJoin(m.genus, ", "),
      m.closed ? "closed" : "NOT closed", m.manifold ? "manifold" : "NOT manifold", m.faces,
      o.upload_bytes, 100.0 * o.upload_bytes / std::max<uint64_t>(1, o.raw_bytes),
      o.mesh_bytes);
}

std::string WarningLines(const std::vector<std::string>& warnings) {
  std::string lines;
  for (const std::string& w : warnings) absl::StrAppend(&lines, "warning: ", w, "\n");
  return lines;
}

}  // namespace membrane::client

// bench_download_memory MESH.drc|MESH.ply: the peak memory of converting a job's mesh for a
// download in the other format (server/mesh_download.h, as the web console's mesh.ply of a
// Draco job and mesh.drc of a PLY job): the high-water mark of this process over what it held
// with the mesh's bytes read, per vertex and per face of the mesh. Run by hand.
#include <cstdio>
#include <string>

#include "core/io/file_bytes.h"
#include "core/pipeline/peak_memory.h"
#include "membrane/v1/reconstruction.pb.h"
#include "server/mesh_download.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: bench_download_memory MESH.drc|MESH.ply\n");
    return 2;
  }
  const std::string path = argv[1];
  const bool ply = path.size() > 4 && path.substr(path.size() - 4) == ".ply";
  absl::StatusOr<std::string> bytes = membrane::ReadFileBytes(path);
  if (!bytes.ok()) {
    std::fprintf(stderr, "%s\n", std::string(bytes.status().message()).c_str());
    return 1;
  }
  membrane::v1::Parameters job;
  job.set_mesh_format(ply ? membrane::v1::MESH_FORMAT_PLY : membrane::v1::MESH_FORMAT_DRACO);
  const int64_t before = membrane::PeakRssBytes();  // the process and the mesh's bytes
  absl::StatusOr<std::string> converted = membrane::server::MeshInFormat(
      *bytes, job, ply ? membrane::v1::MESH_FORMAT_DRACO : membrane::v1::MESH_FORMAT_PLY);
  const int64_t after = membrane::PeakRssBytes();
  if (!converted.ok()) {
    std::fprintf(stderr, "%s\n", std::string(converted.status().message()).c_str());
    return 1;
  }
  // Counted after the measure, which the decode would otherwise raise first.
  absl::StatusOr<membrane::TriangleMesh> mesh = membrane::server::ResultMesh(*bytes, job);
  if (!mesh.ok()) return 1;
  const double vertices = static_cast<double>(mesh->vertices.size());
  const double faces = static_cast<double>(mesh->faces.size());
  std::printf("%s -> %s: %.0f vertices, %.0f faces, %zu -> %zu bytes; peak %lld -> %lld bytes: "
              "%.1f bytes a face\n",
              ply ? "ply" : "drc", ply ? "drc" : "ply", vertices, faces, bytes->size(),
              converted->size(), static_cast<long long>(before),
              static_cast<long long>(after), static_cast<double>(after - before) / faces);
  return 0;
}

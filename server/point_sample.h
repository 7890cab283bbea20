// A sample of a job's input points for the web console, which draws them over the mesh: the
// cloud itself is gone once decoded, and a browser needs no more than a sample.
#ifndef MEMBRANE_SERVER_POINT_SAMPLE_H_
#define MEMBRANE_SERVER_POINT_SAMPLE_H_

#include <cstddef>
#include <string>

#include "core/pipeline/cloud_source.h"
#include "server/job.h"

namespace membrane::server {

// The most points a sample keeps: 240 kB, held with the job until its result expires (about a
// Draco mesh's size), and enough to show in the browser how the points lie about the surface.
inline constexpr size_t kMaxSamplePoints = 20'000;

// Up to `max_points` of `cloud`'s points, evenly strided, as float32 x y z little-endian.
std::string SamplePoints(const PointCloud& cloud, size_t max_points = kMaxSamplePoints);

// A CloudSource that passes on what `inner` reads and keeps SamplePoints of it in `job`
// (Job::SetPointSample).
class SamplingSource : public CloudSource {
 public:
  // `inner` and `job` (not owned) must outlive the source.
  SamplingSource(CloudSource& inner, Job& job) : inner_(inner), job_(job) {}
  absl::StatusOr<PointCloud> Read(const CancelToken& cancel, ProgressRange progress) override;

 private:
  CloudSource& inner_;
  Job& job_;
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_POINT_SAMPLE_H_

// A job's running time limit (--max-job-seconds) asked before the grid is allocated: a job
// whose floor of seconds (core/pipeline/time_estimate.h) is over the limit is refused before
// it runs; otherwise the memory gate it wraps decides. A job slower than its floor is ended by
// the limit itself (JobRunner).
#ifndef MEMBRANE_SERVER_TIME_LIMIT_GATE_H_
#define MEMBRANE_SERVER_TIME_LIMIT_GATE_H_

#include "absl/status/status.h"
#include "core/pipeline/resource_gate.h"
#include "membrane/v1/reconstruction.pb.h"

namespace membrane::server {

// OK when `max_job_seconds` <= 0 (no limit) or when encoding at the job's quantization can
// finish within it (EncodeSecondsFloor); else ResourceExhausted naming the estimate, the flag
// and what to change. Asked at the upload's header, before the upload is taken.
absl::Status CheckEncodeTime(const v1::Parameters& parameters, double max_job_seconds);

class TimeLimitGate : public ResourceGate {
 public:
  // `inner` (not owned) must outlive the gate. `max_job_seconds` <= 0: no limit. `threads`:
  // the job's (ReconstructionOptions::threads).
  TimeLimitGate(ResourceGate& inner, double max_job_seconds, int quantization_bits,
                int threads = 1)
      : inner_(inner), max_seconds_(max_job_seconds), quantization_bits_(quantization_bits),
        threads_(threads) {}

  // ResourceExhausted naming the estimate when GridSecondsFloor of the grid plus the
  // encoding's floor is over the limit; else `inner`'s answer.
  absl::Status AdmitGrid(const PlannedGrid& grid, int64_t points,
                         const CancelToken& cancel) override;
  // `inner`'s answer.
  absl::Status AdmitSurface(const MembraneCounts& membrane, const CancelToken& cancel) override {
    return inner_.AdmitSurface(membrane, cancel);
  }

 private:
  ResourceGate& inner_;
  const double max_seconds_;
  const int quantization_bits_;
  const int threads_;
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_TIME_LIMIT_GATE_H_

// What a reconstruction will cost in time, estimated before it runs, for limits on a job's
// running time (membraned --max-job-seconds). Each estimate is a floor: the fastest rate
// measured, so that a run refused on it could not have finished in time on any cloud; runs
// that are slower than their floor are ended by the limit itself.
#ifndef MEMBRANE_CORE_PIPELINE_TIME_ESTIMATE_H_
#define MEMBRANE_CORE_PIPELINE_TIME_ESTIMATE_H_

#include <cstdint>

namespace membrane {

// Seconds, at least, of the stages up to the surface for a grid of `voxels` (padding
// included) on `threads` threads: 20 ns a voxel, the fastest one-core shrink on the bench
// clouds (21-70 ns a voxel, tests/bench/2026-11-28-shrink.txt), divided by the threads (the
// shrink's word passes share them, and no run is more than `threads` times faster than on
// one); voxelizing, relaxing and the surface come on top.
double GridSecondsFloor(int64_t voxels, int threads = 1);

// Seconds, at least, of encoding a mesh's positions with Draco at `quantization_bits` (0:
// float32, no quantization): Draco's encoder works through tables of 2^bits entries whatever
// the mesh, 25 ns an entry. Measured on a 20k-point sphere's mesh: 0.34 s at 22 bits, 0.90 at
// 24, 2.7 at 26, 8.0 at 28, 43 at 30 (tests/bench/2026-12-02-server-memory.txt).
double EncodeSecondsFloor(int quantization_bits);

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_TIME_ESTIMATE_H_

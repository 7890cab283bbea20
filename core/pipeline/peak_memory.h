// Peak resident memory of this process, for the statistics JSON.
#ifndef MEMBRANE_CORE_PIPELINE_PEAK_MEMORY_H_
#define MEMBRANE_CORE_PIPELINE_PEAK_MEMORY_H_

#include <cstdint>

namespace membrane {

// getrusage(RUSAGE_SELF).ru_maxrss in bytes (Linux reports kibibytes); 0 if the call fails.
int64_t PeakRssBytes();

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_PEAK_MEMORY_H_

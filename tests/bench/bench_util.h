// Small measuring helpers the benchmarks share (bench_shrink, bench_surface, bench_scale,
// bench_memory, server_bench).
#ifndef MEMBRANE_TESTS_BENCH_BENCH_UTIL_H_
#define MEMBRANE_TESTS_BENCH_BENCH_UTIL_H_

#include <cstdint>
#include <ctime>
#include <string>
#include <vector>

#include "absl/strings/string_view.h"

namespace membrane::bench {

// The median of `v` (the mean of the middle two for an even count). `v` must not be empty.
double Median(std::vector<double> v);

// Seconds on the steady clock, for differences only.
double Now();

// Seconds on `clock` (CLOCK_PROCESS_CPUTIME_ID, CLOCK_THREAD_CPUTIME_ID, ...), for differences
// only: the machines are shared, and CPU seconds do not follow their load as wall seconds do.
double ClockSeconds(clockid_t clock);

// The 1, 5 and 15 minute load averages of /proc/loadavg, space separated ("" when unreadable),
// printed beside every figure: these machines are shared.
std::string LoadAverage();

// Parses a --points list such as "100000,1000000" into `out` (replacing what it held). False,
// with `out` unspecified, when the list is empty or an entry is not a positive integer.
bool ParsePointCounts(absl::string_view list, std::vector<int64_t>& out);

}  // namespace membrane::bench

#endif  // MEMBRANE_TESTS_BENCH_BENCH_UTIL_H_

// Small measuring helpers the benchmarks share (bench_shrink, bench_surface, server_bench).
#ifndef MEMBRANE_TESTS_BENCH_BENCH_UTIL_H_
#define MEMBRANE_TESTS_BENCH_BENCH_UTIL_H_

#include <string>
#include <vector>

namespace membrane::bench {

// The median of `v` (the mean of the middle two for an even count). `v` must not be empty.
double Median(std::vector<double> v);

// Seconds on the steady clock, for differences only.
double Now();

// The 1, 5 and 15 minute load averages of /proc/loadavg, space separated ("" when unreadable),
// printed beside every figure: these machines are shared.
std::string LoadAverage();

}  // namespace membrane::bench

#endif  // MEMBRANE_TESTS_BENCH_BENCH_UTIL_H_

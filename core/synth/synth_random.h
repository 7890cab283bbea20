// Random variates for the generators, built directly on std::mt19937_64.
//
// The standard library's distributions are implementation-defined, so the same seed would give
// different clouds with libstdc++ and libc++; these functions fix the arithmetic, so a seed
// names one cloud everywhere.
#ifndef MEMBRANE_CORE_SYNTH_SYNTH_RANDOM_H_
#define MEMBRANE_CORE_SYNTH_SYNTH_RANDOM_H_

#include <cstdint>
#include <random>

#include "core/geometry/vec3.h"

namespace membrane {

// Independent random streams of one seed: stream 0 for a cloud's layout, 1 for its samples,
// so that e.g. the density direction does not change with the point count. Built with
// std::seed_seq, whose mixing the standard specifies, so it is portable.
inline constexpr uint32_t kLayoutStream = 0;
inline constexpr uint32_t kSampleStream = 1;
std::mt19937_64 SeededStream(uint64_t seed, uint32_t stream);

// Uniform in [0, 1), with 53 random bits. Consumes one draw of `rng`.
double Uniform01(std::mt19937_64& rng);

// Standard normal (mean 0, standard deviation 1), by Box-Muller. Consumes two draws.
double StandardNormal(std::mt19937_64& rng);

// Uniformly distributed unit vector. Consumes two draws.
Vec3d RandomUnitVector(std::mt19937_64& rng);

}  // namespace membrane

#endif  // MEMBRANE_CORE_SYNTH_SYNTH_RANDOM_H_

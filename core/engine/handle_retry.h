// The handle retry (docs/engine-decisions.md; ShrinkOptions::retry): when the generations
// left handles, run the small-plate generations again with stricter tunnel sizes and keep the
// result with fewer handles.
//
// Below the guard's tunnel size the chains may open tunnels away from the data that mitosis
// needs (two spheres split this way); most close again before the end, but on a torus-like
// scan some survive as handles across missing data; the wall notches of the n = 2 to 4 plates
// do the same to webs between thin parts that come close. The retry runs the
// generations again from the first one that made a removal the strict sizes refuse, from the
// grid as it was before it, with those tunnels allowed only from the strict sizes, and keeps
// whichever result has fewer handles without fewer shells. Only handles that survive are
// weighed: the tunnels mitosis needs close again (two spheres: genus 0 either way).
#ifndef MEMBRANE_CORE_ENGINE_HANDLE_RETRY_H_
#define MEMBRANE_CORE_ENGINE_HANDLE_RETRY_H_

#include <cstddef>

#include "absl/status/status.h"
#include "core/engine/membrane_shrinker.h"

namespace membrane {

// Runs after every generation of `shrinker` has run once; `start` is the checkpoint saved
// before generation `from`: the first generation, among those whose plate is below the
// strict tunnel size, that allowed a removal the strict sizes refuse (the generations before
// it made the same removals under either rules), or the last one when none did.
// Does nothing more than count when generations [from, end) allowed no removal the strict
// sizes refuse (loose_tunnels: the retry would repeat the same run) or the grid has no
// handle. Otherwise runs them again from `start` with TunnelRules::kStrict and keeps the new
// grid when it has fewer handles and no fewer shells and what it closed (the web) is not
// rimmed by hard voxels for at least options().retry.max_hard_rim: a membrane across a
// scanned hole. Else the first result is restored, grid and counts.
// Fills result.handle_retry. A kept retry's rows (handle_retry set) replace
// result.generations from `from` on and are passed to `on_generation` (may be empty).
// Cancelled when the shrinker's token fires (the shrink is then abandoned).
absl::Status RetryHandles(MembraneShrinker& shrinker, const ShrinkCheckpoint& start,
                          size_t from, const GenerationCallback& on_generation,
                          ShrinkResult& result);

// The status of a shrink cancelled in the handle retry (or while saving its checkpoint).
absl::Status HandleRetryCancelled();

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_HANDLE_RETRY_H_

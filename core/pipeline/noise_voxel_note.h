// The sentence that tells the user the points' noise chose the voxel size (PlanGrid's
// NoiseAwareVoxelSize): the mesh is coarser than formula (1)'s voxel would make it, and why.
// `membrane reconstruct --local` and membraned put it in the statistics' warnings; `membrane
// reconstruct --server`, which sends the size it planned, adds it to the server's.
#ifndef MEMBRANE_CORE_PIPELINE_NOISE_VOXEL_NOTE_H_
#define MEMBRANE_CORE_PIPELINE_NOISE_VOXEL_NOTE_H_

#include <optional>
#include <string>

#include "core/pipeline/memory_estimate.h"

namespace membrane {

// nullopt when `plan`'s voxel size was given or is formula (1)'s; else "the points scatter
// across their surface by S (F of formula (1)'s voxel L1): the voxel size is L, R times formula
// (1)'s, so that the membrane closes over the surface and not over its noise; a voxel size
// given explicitly is used as given".
std::optional<std::string> NoiseVoxelNote(const PlannedGrid& plan);

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_NOISE_VOXEL_NOTE_H_

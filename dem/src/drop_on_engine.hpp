#pragma once
// run_deposition's drop on the one engine (engine.hpp): every drop with velocity Verlet and
// without insertion, the lid included; the drop solver (solver.cpp) runs those with insertion or
// RK4 until they move onto the engine (issue 33).
#include "powderbed/bed/bed.hpp"
#include "powderbed/dem/scene.hpp"
#include "powderbed/dem/solver.hpp"

namespace powderbed::dem::detail {

// Whether the scene's laws need particle rotation (friction.model = history or
// material.rolling > 0), which the drop solver does not carry.
bool needs_rotation(const Scene& scene);

// Whether the drop runs on the engine: velocity Verlet without insertion.
bool runs_on_engine(const Scene& scene, const RunSettings& settings);

// Throws InputError for a scene whose laws need rotation with what only the drop solver has
// (insertion, RK4).
void refuse_rotation_off_engine(const Scene& scene, const RunSettings& settings);

// The drop for settings.t_end or until rest, then the lid, with its trajectory, observer,
// progress and thermo table, summarised as the drop solver's run. run_deposition has checked
// the bed and settings.
RunSummary run_drop_on_engine(bed::Bed& bed, const Scene& scene, const RunSettings& settings);

}  // namespace powderbed::dem::detail

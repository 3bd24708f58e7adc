#pragma once
// run_deposition's drop on the one engine (engine.hpp): velocity Verlet or RK4, insertion
// (insertion.hpp) and the lid (lid_phase.hpp).
#include "powderbed/bed/bed.hpp"
#include "powderbed/dem/scene.hpp"
#include "powderbed/dem/solver.hpp"

namespace powderbed::dem::detail {

// Whether the scene's laws need particle rotation (friction.model = history or
// material.rolling > 0), which the drop solver does not carry.
bool needs_rotation(const Scene& scene);

// Throws InputError for a scene whose laws need rotation with RK4 (Engine::step_rk4 has no
// rotation and no contact history).
void refuse_rotation_with_rk4(const Scene& scene, const RunSettings& settings);

// The drop (or insertion) for settings.t_end or until rest, then the lid, with its trajectory, observer,
// progress and thermo table, summarised as the drop solver's run. run_deposition has checked
// the bed and settings.
RunSummary run_drop_on_engine(bed::Bed& bed, const Scene& scene, const RunSettings& settings);

}  // namespace powderbed::dem::detail

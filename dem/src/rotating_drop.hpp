#pragma once
// A drop whose contact laws need particle rotation (history friction, rolling resistance), run
// on the spreading engine without a tool: run_deposition's route for such a scene.
#include "powderbed/bed/bed.hpp"
#include "powderbed/dem/scene.hpp"
#include "powderbed/dem/solver.hpp"

namespace powderbed::dem::detail {

// Whether the scene's laws need particle rotation (friction.model = history or
// material.rolling > 0), which the drop solver does not carry.
bool needs_rotation(const Scene& scene);

// A drop on the spreading engine (spread.hpp, SpreadSettings::with_tool false) for
// settings.t_end or until rest, with its trajectory, summarised as the drop solver's run.
// Throws InputError for settings out of range (check_run_settings) and for what only the drop
// solver has: the lid, insertion, RK4.
RunSummary run_rotating_drop(bed::Bed& bed, const Scene& scene, const RunSettings& settings);

}  // namespace powderbed::dem::detail

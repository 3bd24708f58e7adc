#pragma once
// The drop solver (solver.cpp: its own step loop over forces.hpp's force loop), which ran every
// drop before the one engine (engine.hpp) did. Kept only as the reference that
// tests/dem/test_engines.cpp runs the engine's drops against (issue 33: the typed equivalence
// test before an engine is deleted); run_deposition no longer calls it.
#include "powderbed/bed/bed.hpp"
#include "powderbed/dem/scene.hpp"
#include "powderbed/dem/solver.hpp"

namespace powderbed::dem::detail {

// run_deposition as it was: the same checks, the drop solver's loop (it refuses the laws that
// need particle rotation).
RunSummary run_on_drop_solver(bed::Bed& bed, const Scene& scene, const RunSettings& settings);

}  // namespace powderbed::dem::detail

#pragma once
// deposit's options (drop, spread, material, walls, effects) and the DEM scene they make: one
// definition for deposit and for build's per-layer spreads.
#include "common/options.hpp"
#include "powderbed/dem/scene.hpp"

namespace powderbed::app {

// Every option of deposit (the common ones, threads, progress, --material, the spread's).
void add_deposit_options(po::options_description& desc);

// The scene of a drop or a spread from the options (material, wall, fluid, contact law,
// friction model, effects).
dem::Scene deposit_scene(const po::variables_map& vm);

}  // namespace powderbed::app

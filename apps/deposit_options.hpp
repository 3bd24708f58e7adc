#pragma once
#include <span>
// deposit's options (drop, spread, material, walls, effects) and the DEM scene they make: one
// definition for deposit and for build's per-layer spreads.
#include "powderbed/bed/json_units.hpp"
#include "common/options.hpp"
#include "powderbed/bed/json.hpp"
#include "powderbed/dem/scene.hpp"
#include "powderbed/dem/solver.hpp"
#include "powderbed/dem/spread.hpp"

namespace powderbed::app {

// What deposit's options of a plain type are bound to (po::value<T>(&field), defaults: these
// structs' values): the scene, a drop's run settings and a spread's settings. parse_options's
// po::notify fills them, so they outlive the parse.
struct DepositOptions {
  dem::Scene scene;
  dem::RunSettings run;
  dem::SpreadSettings spread;
};

// Every option of deposit (the common ones, threads, progress, --material, the spread's), those
// of a plain type bound to `bound`.
void add_deposit_options(po::options_description& desc, DepositOptions& bound);

// The scene of a drop or a spread: `bound` (DepositOptions::scene) with what the options give
// as words (contact law, friction model), the linear law's stiffness checked and the effects.
dem::Scene deposit_scene(const po::variables_map& vm, const dem::Scene& bound);

// The units of every number deposit's --json summaries hold, drop and spread (common/json_units).
std::span<const bed::UnitEntry> deposit_units();

// The contact laws of deposit's --json summary, the same for a drop and a spread (after
// dem's run or spread fields, summary_json.hpp): the softening and the laws' names.
void write_contact_laws(bed::JsonWriter& j, double young_scale, const dem::Scene& scene);

}  // namespace powderbed::app

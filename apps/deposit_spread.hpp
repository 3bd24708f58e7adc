#pragma once
// deposit's spreading mode (docs/deposit-spread.md): a recoater scene (recoater.tool = blade |
// roller) spreads its supply layer after layer instead of dropping a bed. Its options, the
// test that a run asks for it, and the run itself, kept apart from the drop's code.
#include "common/options.hpp"
#include "powderbed/bed/bed.hpp"
#include "powderbed/dem/scene.hpp"
#include "powderbed/dem/solver.hpp"
#include "powderbed/dem/spread.hpp"

#include <optional>

namespace powderbed::app {

// recoater.*, supply.*, --layers, --tool-forces, and the scene options the drop does not use
// (friction.model, material.rolling: both solvers read them, only the spread accepts history
// friction and rolling resistance).
void add_spread_options(po::options_description& desc);
// Whether the options name a recoater tool.
bool spread_requested(const po::variables_map& vm);
// The spread's box: --domain with --periodic (y unless given) for a new bed, or `given` (an --in
// bed's); throws InputError for a bad --periodic or a box periodic along x (the tool's travel).
bed::Domain spread_box(const po::variables_map& vm,
                       std::optional<bed::Domain> given = std::nullopt);
// The spread's settings from the options: the tool, the supply (seeded per layer from `seed`),
// --layers, the overflow, the layer thickness, the softening and the time step.
dem::SpreadSettings spread_settings(const po::variables_map& vm, std::uint64_t seed);
// The provenance a spread bed carries: `program` and its command line, --seed, the resolved
// scene and the contact law as made (softening included).
void set_spread_provenance(bed::Bed& b, const po::variables_map& vm, const dem::Scene& scene,
                           const char* program, int argc, char** argv);
// Runs the spread and writes its beds; returns the exit status.
int run_spread(const po::variables_map& vm, int argc, char** argv);

// Whether a drop needs particle rotation (friction.model = history or material.rolling > 0),
// which only the spreading run's loop has.
bool rotating(const dem::Scene& scene);
// A drop of `settings.t_end` in that loop, without a tool (spread.hpp, SpreadSettings::with_tool
// false), summarised as the drop solver's run. Throws InputError for settings out of range
// (dem::check_run_settings) and for what only the drop solver has: --until-rest, the lid,
// insertion, RK4, a trajectory.
dem::RunSummary run_rotating_drop(bed::Bed& bed, const dem::Scene& scene,
                                  const dem::RunSettings& settings);

}  // namespace powderbed::app

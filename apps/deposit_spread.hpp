#pragma once
// deposit's spreading mode (docs/deposit-spread.md): a recoater scene (recoater.tool = blade |
// roller) spreads its supply layer after layer instead of dropping a bed. Its options, the
// test that a run asks for it, and the run itself, kept apart from the drop's code.
#include "common/options.hpp"
#include "powderbed/bed/bed.hpp"
#include "powderbed/dem/scene.hpp"
#include "powderbed/dem/solver.hpp"

namespace powderbed::app {

// recoater.*, supply.*, --layers, --tool-forces, and the scene options the drop does not use
// (friction.model, material.rolling: both solvers read them, only the spread accepts history
// friction and rolling resistance).
void add_spread_options(po::options_description& desc);
// Whether the options name a recoater tool.
bool spread_requested(const po::variables_map& vm);
// Runs the spread and writes its beds; returns the exit status.
int run_spread(const po::variables_map& vm, int argc, char** argv);

// Whether a drop needs particle rotation (friction.model = history or material.rolling > 0),
// which only the spreading run's loop has.
bool rotating(const dem::Scene& scene);
// A drop of `settings.t_end` in that loop, without a tool (spread.hpp, SpreadSettings::with_tool
// false), summarised as the drop solver's run. Throws InputError for what only the drop solver
// has: --until-rest, the lid, insertion, RK4, a trajectory.
dem::RunSummary run_rotating_drop(bed::Bed& bed, const dem::Scene& scene,
                                  const dem::RunSettings& settings);

// The scene of a drop or a spread from the options (defined in deposit.cpp).
dem::Scene deposit_scene(const po::variables_map& vm);

}  // namespace powderbed::app

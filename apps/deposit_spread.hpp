#pragma once
// deposit's spreading mode (docs/deposit-spread.md): a recoater scene (recoater.tool = blade |
// roller) spreads its supply layer after layer instead of dropping a bed. Its options, the
// test that a run asks for it, and the run itself, kept apart from the drop's code.
#include "common/options.hpp"
#include "powderbed/bed/bed.hpp"
#include "powderbed/dem/scene.hpp"
#include "powderbed/dem/solver.hpp"
#include "powderbed/dem/spread.hpp"

#include <memory>
#include <optional>

namespace powderbed::app {

struct DepositOptions;  // deposit_options.hpp

// recoater.*, supply.*, --layers, --tool-forces, and the scene options the drop does not use
// (friction.model, material.rolling: both solvers read them, only the spread accepts history
// friction and rolling resistance). The options of a plain type are bound to `spread`'s and
// `scene`'s fields (defaults: their values).
void add_spread_options(po::options_description& desc, dem::SpreadSettings& spread,
                        dem::Scene& scene);
// Whether the options name a recoater tool.
bool spread_requested(const po::variables_map& vm);

// The supply of layer `layer` (1: the first) of a strip `width` across: supply.count particles,
// or a solid volume: supply.volume, or with supply.dosing d the powder of d times the layer's
// nominal volume at the supply's bulk density φ_b, d φ_b (recoater.end - recoater.start) width t,
// t the first layer's gap and then the plate's drop (recoater.layer-thickness): a machine's
// dosing factor, the dose piston's rise over the build piston's drop. InputError when not
// exactly one is given or a value is out of range.
struct SupplyAmount {
  std::size_t count = 0;
  double volume = 0;  // m^3 of solid
};
SupplyAmount supply_amount(const po::variables_map& vm, std::uint64_t layer, double width);
// The spread's box: --domain with --periodic (y unless given) for a new bed, or `given` (an --in
// bed's); throws InputError for a bad --periodic or a box periodic along x (the tool's travel).
bed::Domain spread_box(const po::variables_map& vm,
                       std::optional<bed::Domain> given = std::nullopt);
// The spread's settings: `bound` (the settings add_spread_options bound: the tool's numbers, the
// supply region, --layers, the overflow, the layer thickness) with the tool's shape, the supply
// (seeded per layer from `seed`), the softening, the time step and the thermo table of --thermo
// and --log (common/thermo_table.hpp; `table`, when given, receives it for the run's summary).
class ThermoTable;
dem::SpreadSettings spread_settings(const po::variables_map& vm, const dem::SpreadSettings& bound,
                                    std::uint64_t seed,
                                    std::shared_ptr<ThermoTable>* table = nullptr);
// The provenance a spread bed carries: `program` and its command line, --seed, the resolved
// scene and the contact law as made (softening included).
void set_spread_provenance(bed::Bed& b, const po::variables_map& vm, const dem::Scene& scene,
                           const char* program, int argc, char** argv);
// Runs the spread of the options (`bound`: what add_deposit_options bound) and writes its beds;
// returns the exit status.
int spread_command(const po::variables_map& vm, const DepositOptions& bound, int argc, char** argv);

}  // namespace powderbed::app

#pragma once
// build --spread-engine liggghts [--mpi N] (docs/build.md "Spreading in LIGGGHTS"): each layer's
// spread runs in LIGGGHTS instead of dem::run_spread. The layer starts as deposit starts it (the
// supply placed by dem::add_layer_supply, the time step run_spread would take), goes out as the
// deck deposit --export-deck writes (spread_deck.hpp, one layer, the fused solid as the floor
// STL), runs under `liggghts` or `mpirun -np N liggghts` in its own folder, and comes back
// through the LAMMPS dump reader as the layer the rest of build expects.
#include <cstdint>
#include <optional>
#include <string>

#include "common/options.hpp"
#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/psd.hpp"
#include "powderbed/dem/scene.hpp"
#include "powderbed/dem/spread.hpp"

namespace powderbed::app {

struct LiggghtsEngine {
  unsigned ranks = 1;
  std::string liggghts, mpirun;  // resolved on PATH
  std::uint64_t seed = 1;
  bed::Psd psd;                  // the supply's, for the deck's insertion table
  std::size_t supply_count = 0;
  double supply_volume = 0;
};

// --spread-engine deposit|liggghts, --mpi N.
void add_spread_engine_options(po::options_description& desc);
// The LIGGGHTS engine when --spread-engine liggghts (nullopt: deposit's own); `spread` is the
// spread stage's options (the supply). Throws InputError (exit 2, one line) for an unknown
// engine, --mpi 0 or --mpi without liggghts, and a liggghts (or, for N > 1, mpirun) that is not
// on PATH: checked before layer 1.
std::optional<LiggghtsEngine> spread_engine(const po::variables_map& vm, const po::variables_map& spread,
                                            std::uint64_t seed);
// Spreads layer `layer` of `settings` (one layer) on `bed` in LIGGGHTS inside `folder` (made
// here), continuing `state` (its floor and time step; LIGGGHTS keeps no contact history across
// layers). Returns the summary run_spread would (one layer; its steps, the overflow LIGGGHTS
// deleted, the particles it lost, the state with zero spins and histories). Throws
// NumericalError when LIGGGHTS fails, naming its log.
dem::SpreadSummary liggghts_spread_layer(const LiggghtsEngine& engine, bed::Bed& bed,
                                         const dem::Scene& scene, const dem::SpreadSettings& settings,
                                         const std::optional<dem::SpreadState>& state,
                                         std::uint64_t layer, const std::string& folder);

}  // namespace powderbed::app

#pragma once
// A recoater spread as a LIGGGHTS or LAMMPS deck (docs/decks.md "Spreading decks"): what deposit
// --export-deck writes in spreading mode and build --spread-engine liggghts runs each layer.
// The laws are the drop deck's (common/deck_export.hpp) plus rotation, history friction and
// rolling resistance; the tool, supply and layers are the spread settings'.
#include <cstdint>
#include <string>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/deck.hpp"
#include "powderbed/bed/psd.hpp"
#include "powderbed/dem/scene.hpp"
#include "powderbed/dem/spread.hpp"

namespace powderbed::app {

// The time step run_spread takes for `bed` (settings.dt when given, checked against the stable
// bound unless settings.unsafe_dt; else 0.2 x the bound).
double spread_time_step(const bed::Bed& bed, const dem::Scene& scene, const dem::SpreadSettings& s);
// Writes DATA_PATH, in.<stem>.<engine> and (LIGGGHTS) the STL files for `layers` layers from `bed` (its
// first layer's supply in it), layer `first` of the spread being the deck's layer 1 (the tool
// raised by first - 1 layer thicknesses), on `floor` (empty: the plate).
struct SpreadDeckRequest {
  bed::DeckEngine engine = bed::DeckEngine::liggghts;
  const bed::Bed* bed = nullptr;
  const dem::Scene* scene = nullptr;
  const dem::SpreadSettings* settings = nullptr;
  const bed::Psd* psd = nullptr;
  std::uint64_t seed = 1, first = 1, layers = 1;
  double dt = 0;
  std::size_t supply_count = 0;
  double supply_volume = 0;
  bed::HeightMap floor;
  std::string made_by;  // for the deck's header: which run wrote it
};
void write_spread_deck(const SpreadDeckRequest& r, const std::string& data_path);

}  // namespace powderbed::app

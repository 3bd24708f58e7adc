// A recoater spread as a LIGGGHTS or LAMMPS deck (spread_deck.hpp).
#include "spread_deck.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "common/deck_export.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/dem/recoater.hpp"
#include "powderbed/dem/time_step.hpp"

namespace powderbed::app {

namespace {

// Bins of the supply's PSD (layers after the first: LIGGGHTS's discrete distribution, LAMMPS's
// create_atoms bin by bin): equal
// widths in radius between its bounds, each at its middle radius with its number fraction.
constexpr int kPsdBins = 10;

std::vector<std::pair<double, double>> psd_bins(const bed::Psd& psd) {
  const double lo = psd.min_radius(), hi = psd.max_radius();
  if (!(hi > lo)) return {{lo, 1.0}};
  std::vector<std::pair<double, double>> bins;
  for (int k = 0; k < kPsdBins; ++k) {
    const double a = lo + (hi - lo) * k / kPsdBins, b = lo + (hi - lo) * (k + 1) / kPsdBins;
    const double w = psd.cdf_radius(b) - psd.cdf_radius(a);
    if (w > 0) bins.emplace_back(0.5 * (a + b), w);
  }
  return bins;
}

bed::DeckTool deck_tool(const dem::Recoater& t, double gap) {
  const dem::ToolProfile p = dem::tool_profile(t, 0.0);
  bed::DeckTool d;
  d.roller = t.shape == dem::ToolShape::roller;
  d.half_width = p.half_width;
  d.rounding = p.rounding;
  d.gap = gap;
  d.start = t.start;
  d.end = t.end;
  d.speed = t.speed;
  d.omega = t.omega;
  d.delay = t.delay;
  d.settle = t.settle;
  return d;
}

}  // namespace

double spread_time_step(const bed::Bed& bed, const dem::Scene& scene, const dem::SpreadSettings& s) {
  const dem::TimeStepBound bound = dem::time_step_bound(bed, scene, s.young_scale);
  if (s.dt > 0 && s.dt > bound.stable && !s.unsafe_dt)
    throw InputError(fmt::format("--dt: {:g} s is above the stable bound {:g} s (accepted: dt <= "
                                 "{:g} s, or add --unsafe-dt)", s.dt, bound.stable, bound.stable));
  return s.dt > 0 ? s.dt : bound.recommended;
}

void write_spread_deck(const SpreadDeckRequest& r, const std::string& data_path) {
  const dem::Scene& scene = *r.scene;
  const dem::SpreadSettings& s = *r.settings;
  bed::DeckLaws laws = run_deck_laws(scene, s.young_scale, r.dt, r.made_by);
  laws.rotation = true;
  laws.tangential_history = scene.friction_model == dem::FrictionModel::history && laws.friction > 0;
  laws.rolling = scene.material.rolling;
  laws.origin.push_back(fmt::format("friction.model = {}, material.rolling = {}: {}",
                                    laws.tangential_history ? "history" : "sliding", laws.rolling,
                                    r.made_by));
  bed::SpreadDeck deck;
  deck.engine = r.engine;
  // the deck's layer 1 is the spread's layer `first`: the plate has gone down first - 1 layers
  deck.tool = deck_tool(s.tool, s.tool.gap + static_cast<double>(r.first - 1) * s.layer_thickness);
  deck.layers = r.layers;
  deck.layer_thickness = s.layer_thickness;
  deck.remove_overflow = s.remove_overflow;
  deck.supply_x0 = s.supply_x0;
  deck.supply_x1 = s.supply_x1;
  deck.supply_height = s.supply_height;
  deck.supply_count = r.supply_count;
  deck.supply_volume = r.supply_volume;
  deck.psd_bins = psd_bins(*r.psd);
  deck.seed = r.seed;
  deck.floor = r.floor;
  bed::write_spread_deck(*r.bed, laws, deck, data_path);
}

}  // namespace powderbed::app

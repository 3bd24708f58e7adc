// Coalescence of molten particles (wetting.hpp has the time scales): two drops in contact merge
// on the inertial–capillary time √(ρ r³ / γ) ≈ 3 µs for r = 13.5 µm of liquid 316L (Eggers,
// Lister & Stone, J. Fluid Mech. 401:293, 1999), shorter than the tens of microseconds a
// particle under the beam stays molten, so two wholly molten particles in contact become one
// drop at once. Without it a molten particle resting on others keeps only the bridges to them
// and, carrying the beam's heat on its own, runs to its boiling point and evaporates: in a
// dosed layer, where powder lies several particles deep, that was tens of percent of the melt.
// A drop that touches the pool (a particle that merged into it) is part of the melt's surface:
// it exchanges with the pool's top nodes and merges into it once wholly molten (wetting.cpp).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "powderbed/thermal/beer_lambert_laser.hpp"
#include "powderbed/thermal/vapour_depression.hpp"
#include "powderbed/thermal/wetting.hpp"
#include "solver_state.hpp"

namespace powderbed::thermal {

namespace {

// The drop's size follows its volume (r³ adds at one density); it keeps the bottom of the drop
// that survives, so it rests where that one rested and its substrate contact stays where it was.
void grow_drop(Sinter::State& s, std::size_t keep, std::size_t drop) {
  const double bottom = s.z[keep] - s.radius[keep];
  const double r = std::cbrt(std::pow(s.radius[keep], 3) + std::pow(s.radius[drop], 3));
  s.radius[keep] = r;
  s.z[keep] = bottom + r;
  s.area[keep] = std::numbers::pi * r * r;
  s.laser_factor[keep] =
      particle_laser_factor(s.scene.absorptivity, s.area[keep], s.beta, s.surface.depth[keep]);
  if (!s.scene.has(kDepression)) return;
  const double t_d = depression_temperature(s.vapour, s.scene.surface_tension, r);
  s.particle_depression_temperature[keep] = t_d;
  s.particle_depression_enthalpy[keep] = s.per_kg.enthalpy(t_d);
}

// The contacts of `drop` become those of `keep`: its pairs (the one between them closes), its
// substrate contact where `keep` has none, its wetted contacts. A neighbour of both keeps both
// necks: the drop is larger than either particle was.
void take_contacts(Sinter::State& s, std::size_t keep, std::size_t drop) {
  for (const auto p : s.pairs_of[drop]) {
    ContactPair& pair = s.net.pairs[p];
    std::uint32_t& end = pair.i == drop ? pair.i : pair.j;
    const std::uint32_t other = pair.i == drop ? pair.j : pair.i;
    if (other == keep) {
      pair.shape = 0;
      continue;
    }
    end = static_cast<std::uint32_t>(keep);
    s.pairs_of[keep].push_back(p);
  }
  s.pairs_of[drop].clear();
  const std::int64_t c = s.substrate_of[drop];
  if (c >= 0 && s.substrate_of[keep] < 0) {
    s.net.substrate[static_cast<std::size_t>(c)].particle = static_cast<std::uint32_t>(keep);
    s.substrate_of[keep] = c;
  }
  s.substrate_of[drop] = -1;
  for (auto& w : s.wetted)
    if (w.particle == drop) w.particle = static_cast<std::uint32_t>(keep);
}

// `drop` merges into `keep`: mass and enthalpy add (the energy and the mass are the same before
// and after, exactly), the peak is the hotter one's.
void absorb(Sinter::State& s, std::size_t keep, std::size_t drop) {
  const double m = s.mass[keep] + s.mass[drop];
  s.h[keep] = (s.mass[keep] * s.h[keep] + s.mass[drop] * s.h[drop]) / m;
  s.mass[keep] = m;
  s.initial_mass[keep] += s.initial_mass[drop];
  s.peak[keep] = std::max(s.peak[keep], s.peak[drop]);
  s.lit_time[keep] = std::max(s.lit_time[keep], s.lit_time[drop]);
  grow_drop(s, keep, drop);
  take_contacts(s, keep, drop);
  s.mass[drop] = 0;
  s.initial_mass[drop] = 0;
  s.h[drop] = 0;
  s.gone[drop] = 1;
  s.coalesced_into[drop] = static_cast<std::uint32_t>(keep);
  ++s.coalesced_count;
  ++s.gone_count;  // the tracer drops it and resizes `keep`
  particle_enthalpy_changed(s, keep);
  recheck_particle_step(s, keep);
}

// Of two drops the one lower down survives (the upper one runs down into it); ties: the first.
bool survives(const Sinter::State& s, std::size_t a, std::size_t b) {
  const double bottom_a = s.z[a] - s.radius[a], bottom_b = s.z[b] - s.radius[b];
  return bottom_a != bottom_b ? bottom_a < bottom_b : a < b;
}

}  // namespace

void coalesce_molten(Sinter::State& s) {
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    if (s.gone[i] || !wholly_molten(s, i)) continue;
    // By index: absorbing a neighbour appends its pairs to i's, which are then met in turn.
    for (std::size_t n = 0; n < s.pairs_of[i].size() && !s.gone[i]; ++n) {
      const ContactPair& pair = s.net.pairs[s.pairs_of[i][n]];
      const std::size_t j = pair.i == i ? pair.j : pair.i;
      if (j == i || s.gone[j] || !wholly_molten(s, j)) continue;
      if (survives(s, i, j)) absorb(s, i, j);
      else absorb(s, j, i);
    }
  }
}

// The contact keeps the conductance its pair had, now with the pool's top nodes in the toucher's
// disc around the point where the two touched (when it merges, its volume goes under its centre:
// merge_into_pool).
void touch_pool(Sinter::State& s, std::size_t merged) {
  for (const auto p : s.pairs_of[merged]) {
    ContactPair& pair = s.net.pairs[p];
    const std::size_t j = pair.i == merged ? pair.j : pair.i;
    if (s.gone[j] || pair.shape <= 0) continue;
    const double t = s.radius[merged] / (s.radius[merged] + s.radius[j]);
    const double cx = s.x[merged] + t * (s.x[j] - s.x[merged]);
    const double cy = s.y[merged] + t * (s.y[j] - s.y[merged]);
    s.wetted.push_back({static_cast<std::uint32_t>(j), pair.shape, 0.0,
                        top_footprint(s.g, cx, cy, s.radius[j]), true});
    pair.shape = 0;
  }
}

}  // namespace powderbed::thermal

// Molten particles wet what they touch (wetting.hpp has the model and its sources). Checked
// once per grid step, after the particle steps: a particle that has just reached T_m spreads
// its substrate contact into a spherical cap and, with each neighbour that is molten too, grows
// a liquid bridge. Bridges stay in the explicit particle network (their conductance is within
// the particles' stable step, which is re-checked); a spread substrate contact can be far
// stiffer than the grid step allows, so it leaves the network and is exchanged exactly
// (exact_exchange) with the top nodes under the cap.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "powderbed/bed/sphere_volume.hpp"
#include "powderbed/thermal/contact_conduction.hpp"
#include "powderbed/thermal/contact_temperature.hpp"
#include "powderbed/thermal/wetting.hpp"
#include "solver_state.hpp"

namespace powderbed::thermal {

namespace {

// Whether melt at t_melt remelts the solid at t_solid it touches: their interface sits at the
// contact temperature of the two (contact_temperature.hpp), and the solid melts where that is at
// or above T_m. On 316L a particle just molten on a 363 K plate meets it at T_c ≈ 1200 K and
// arrests; past ≈ 2500 K (≈ 2300 K on solid at 1000 K) its melt remelts the solid under it, and
// any melt does on solid already at T_m.
bool melt_remelts(const Sinter::State& s, double t_melt, double t_solid) {
  const double t_m = s.scene.phase_change.melting_point;
  if (t_solid >= t_m) return true;
  const Material& m = s.material;
  const double liquid =
      effusivity(m.conductivity(t_melt), m.density(t_melt), m.liquid_specific_heat());
  const double solid = effusivity(m.solid_conductivity(t_solid), m.solid_density(t_solid),
                                  m.solid_specific_heat(t_solid));
  return contact_temperature(liquid, t_melt, solid, t_solid) >= t_m;
}

// Whether the melt of particle i remelts the solid under its cap (the mean of the top nodes the
// cap would cover).
bool interface_remelts(const Sinter::State& s, std::size_t i,
                       const std::vector<std::pair<std::size_t, double>>& footprint) {
  double t_solid = 0;
  for (const auto& [column, weight] : footprint)
    t_solid += weight * s.node_temperature[top_node(s, column)];
  return melt_remelts(s, s.temperature[i], t_solid);
}

// The spherical cap particle i's melt makes on the plate at the contact angle, at its volume now.
SpreadCap particle_cap(const Sinter::State& s, std::size_t i) {
  return spherical_cap(bed::sphere_volume(s.radius[i]),
                       s.scene.contact_angle * std::numbers::pi / 180);
}

// The area of the cap's base left on the plate: each column is wetted once at most, so a cap
// gets only what earlier caps left of the columns under it (and takes it).
double claim_area(Sinter::State& s, const std::vector<std::pair<std::size_t, double>>& footprint,
                  double area) {
  double got = 0;
  for (const auto& [column, weight] : footprint) {
    double& left = s.unwetted_area[column];
    const double take = std::min(left, weight * area);
    left -= take;
    got += take;
  }
  return got;
}

// A molten particle on the substrate: where its melt remelts the solid under it (interface_remelts)
// the melt spreads into a spherical cap at the contact angle (Young); elsewhere the contact line
// arrests (splat physics: the interface sits below T_m) and the particle meets the plate over the
// same base through the interfacial conductance h_c in series. Arrested contacts spread once
// the interface under them reaches T_m (spread_molten), as the particle heats or the solid does.
void spread_on_substrate(Sinter::State& s, std::size_t i) {
  const std::int64_t c = s.substrate_of[i];
  if (c < 0) return;
  SubstrateContact& contact = s.net.substrate[static_cast<std::size_t>(c)];
  const SpreadCap cap = particle_cap(s, i);
  auto footprint = top_footprint(s.g, s.x[i], s.y[i], cap.base_radius);
  const bool remelted = interface_remelts(s, i, footprint);
  if (contact.shape == 0) {  // wetted before: an arrested contact spreads once remelted
    if (!remelted) return;
    for (auto& w : s.wetted) {
      if (w.particle != i || w.interface == 0) continue;
      w.interface = 0;
      --s.arrested;
    }
    return;
  }
  const double base = std::numbers::pi * cap.base_radius * cap.base_radius;
  const double area = claim_area(s, footprint, base);
  // The plate under it is wetted already (by caps that have merged, or will): the melt meets
  // that melt through the contact it had, and joins the pool as a cap would.
  const bool claimed = area <= 0;
  const double interface =
      remelted ? 0 : 1 / (s.scene.arrested_conductance * (claimed ? base : area));
  if (!remelted) ++s.arrested;
  s.wetted.push_back({static_cast<std::uint32_t>(i),
                      claimed ? contact.shape : area / cap.centroid_height, interface,
                      std::move(footprint), claimed});
  contact.shape = 0;  // out of the explicit network: wetted_exchange carries it
}

}  // namespace

void recheck_particle_step(Sinter::State& s, std::size_t i) {
  double conductance = 0;
  for (const auto p : s.pairs_of[i]) conductance += s.k_max * s.net.pairs[p].shape;
  if (s.substrate_of[i] >= 0)
    conductance += s.k_max * s.net.substrate[static_cast<std::size_t>(s.substrate_of[i])].shape;
  if (conductance <= 0) return;
  const double bound = s.scene.safety * s.mass[i] * s.per_kg.min_capacity() / conductance;
  const auto needed = static_cast<std::size_t>(std::ceil(s.dt / bound));
  s.substeps_stable = std::max(s.substeps_stable, needed);
  s.substeps = std::max(s.substeps, s.substeps_stable);
}

void setup_wetting(Sinter::State& s) {
  const std::size_t n = s.x.size();
  s.unwetted_area.assign(s.g.nx * s.g.ny, s.g.dx * s.g.dy);
  s.merged.assign(n, 0);
  s.coalesced_into.resize(n);
  for (std::size_t i = 0; i < n; ++i) s.coalesced_into[i] = static_cast<std::uint32_t>(i);
  s.molten.assign(n, 0);
  s.pairs_of.assign(n, {});
  s.substrate_of.assign(n, -1);
  for (std::size_t p = 0; p < s.net.pairs.size(); ++p) {
    s.pairs_of[s.net.pairs[p].i].push_back(static_cast<std::uint32_t>(p));
    s.pairs_of[s.net.pairs[p].j].push_back(static_cast<std::uint32_t>(p));
  }
  for (std::size_t c = 0; c < s.net.substrate.size(); ++c)
    s.substrate_of[s.net.substrate[c].particle] = static_cast<std::int64_t>(c);
}

namespace {

// A wholly molten particle whose cap has spread (its melt remelted the solid) is part of the
// pool: its mass and enthalpy go into the free top nodes under the cap, whose columns rise by
// its volume (raise_column), it leaves the network and the beam (the maps are traced anew
// without it: the pool's surface is the substrate's), its mass stays booked for fusion
// (docs/sinter.md "Fusion").
void merge_into_pool(Sinter::State& s, const Sinter::State::WettedContact& w) {
  const SubstrateGeometry& g = s.g;
  const std::size_t i = w.particle;
  // The melt spreads over the base of its cap, or a drop that touched the pool over its own
  // disc, at its volume now: a drop that has grown by coalescence since it first touched covers
  // more than its first footprint (left on that, 30 particles' melt stood 190 um on 3 x 3 cells).
  const double reach = w.through_pool ? s.radius[i] : particle_cap(s, i).base_radius;
  const auto footprint = top_footprint(g, s.x[i], s.y[i], reach);
  // The free nodes under the cap take it all (a Dirichlet column holds no melt); a cap on
  // Dirichlet columns alone stays a particle.
  double free = 0;
  for (const auto& [column, weight] : footprint)
    if (!g.fixed_column(column)) free += weight;
  if (free <= 0) return;
  const double rho0 = s.material.density(s.scene.initial_temperature);
  for (const auto& [column, weight] : footprint) {
    if (g.fixed_column(column)) continue;
    // The melt joins the top node: its volume m w / rho0 (as fusion books it) and its enthalpy.
    const std::size_t node = top_node(s, column);
    const double share = weight / free;
    const double added = share * s.mass[i] / rho0, before = node_volume(s, node);
    s.e[node] = (s.e[node] * before + share * s.mass[i] * s.h[i]) / (before + added);
    raise_column(s, column, added / (g.dx * g.dy));
  }
  s.h[i] = 0;
  s.gone[i] = 1;
  s.merged[i] = 1;
  ++s.merged_count;
  ++s.gone_count;  // the tracer removes it
}

// The spread caps (and contacts with the pool) whose particle is wholly molten merge into the
// pool; what touched a merged particle touches the pool from then on (touch_pool).
void merge_molten(Sinter::State& s) {
  std::vector<std::size_t> pooled;
  for (const auto& w : s.wetted) {
    if (w.interface > 0 || s.gone[w.particle] || !wholly_molten(s, w.particle)) continue;
    merge_into_pool(s, w);
    if (s.merged[w.particle]) pooled.push_back(w.particle);
  }
  for (const std::size_t i : pooled) touch_pool(s, i);
}

// Whether the melt of particle `molten` wets its neighbour `other`: melt meets melt, or solid it
// remelts (melt_remelts).
bool wets(const Sinter::State& s, std::size_t molten, std::size_t other) {
  const double t_other = s.temperature[other];
  return t_other >= s.scene.phase_change.melting_point ||
         melt_remelts(s, s.temperature[molten], t_other);
}

// The shape factor of pair p once the melt of `molten` meets the other particle: where it wets,
// a liquid bridge whose neck has grown to the smaller sphere's radius; where it does not, the
// same neck behind the interfacial conductance h_c, the contact line arrested as on the plate
// (an interface resistance 1/(h_c A) is that of a slab of the metal k/h_c thick: ~27 µm of 316L
// at T_m for h_c = 1e6 W/m²K, against centre distances of ~25 µm).
double melt_contact_shape(const Sinter::State& s, const ContactPair& pair, std::size_t molten,
                          bool wetted) {
  const std::size_t other = pair.i == molten ? pair.j : pair.i;
  const double d = std::hypot(s.x[molten] - s.x[other], s.y[molten] - s.y[other],
                              s.z[molten] - s.z[other]);
  const double t_m = s.scene.phase_change.melting_point;
  const double slab = wetted ? 0.0 : s.material.conductivity(t_m) / s.scene.arrested_conductance;
  return conduction_shape_factor(bridge_radius(s.radius[molten], s.radius[other]), d + slab);
}

// Particle `molten` has just melted: pair p grows to its melt contact (a contact only grows);
// an arrested one joins the list respread_pairs watches. Returns whether it grew.
bool wet_pair(Sinter::State& s, std::uint32_t p, std::size_t molten) {
  ContactPair& pair = s.net.pairs[p];
  const std::size_t other = pair.i == molten ? pair.j : pair.i;
  if (s.gone[other] || pair.shape <= 0) return false;
  const bool wetted = wets(s, molten, other);
  const double shape = melt_contact_shape(s, pair, molten, wetted);
  if (shape <= pair.shape) return false;
  pair.shape = shape;
  if (wetted) ++s.bridges;
  else s.arrested_pairs.push_back(p);
  recheck_particle_step(s, other);
  return true;
}

// Arrested pairs whose melt now wets the other side (it heated, or the other did) become
// bridges; the rest stay watched (a frozen one may melt again) until a particle has gone.
void respread_pairs(Sinter::State& s) {
  const double t_m = s.scene.phase_change.melting_point;
  std::size_t kept = 0;
  for (const std::uint32_t p : s.arrested_pairs) {
    ContactPair& pair = s.net.pairs[p];
    if (s.gone[pair.i] || s.gone[pair.j]) continue;
    const std::size_t molten = s.temperature[pair.i] >= s.temperature[pair.j] ? pair.i : pair.j;
    if (s.temperature[molten] < t_m || !wets(s, molten, molten == pair.i ? pair.j : pair.i)) {
      s.arrested_pairs[kept++] = p;
      continue;
    }
    pair.shape = std::max(pair.shape, melt_contact_shape(s, pair, molten, true));
    ++s.bridges;
    recheck_particle_step(s, pair.i);
    recheck_particle_step(s, pair.j);
  }
  s.arrested_pairs.resize(kept);
}

}  // namespace

void spread_molten(Sinter::State& s) {
  const double t_m = s.scene.phase_change.melting_point;
  merge_molten(s);
  coalesce_molten(s);
  respread_pairs(s);
  if (s.arrested > 0) {  // arrested contacts whose solid has remelted since
    for (std::size_t k = 0; k < s.wetted.size(); ++k)
      if (s.wetted[k].interface > 0 && !s.gone[s.wetted[k].particle])
        spread_on_substrate(s, s.wetted[k].particle);
  }
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    const bool now = !s.gone[i] && s.temperature[i] >= t_m;
    const bool melted = now && !s.molten[i];
    s.molten[i] = now;
    if (!melted) continue;
    spread_on_substrate(s, i);
    bool grown = false;
    for (const auto p : s.pairs_of[i]) grown = wet_pair(s, p, i) || grown;
    if (grown) recheck_particle_step(s, i);
  }
}

// Capacity of a body between its temperature t and the other body's t_other, from its enthalpy
// curve (the secant): the apparent heat capacity at t alone would let a particle leaving its
// melting window give up far more than it holds between the two temperatures.
double secant_capacity(const EnthalpyCurve& curve, double t, double t_other) {
  const double span = t_other - t;
  if (std::abs(span) < 1e-6) return curve.capacity(t);
  return (curve.enthalpy(t_other) - curve.enthalpy(t)) / span;
}

namespace {

// The exchange, with conductivities that follow temperature (Variable) or are held at T0: a
// template argument, chosen once per step (wetted_exchange), not per contact. The cap touches
// each node under it over its share w_q of the base, so it is w_q of the cap's conductance to
// that node alone, exchanged exactly pair by pair: a node's heat follows its own difference to
// the particle (one exchange with the nodes' mean, shared out by w_q, would draw heat from a
// node colder than the particle whenever the others are hotter and swing it below T0).
template <bool Variable>
void exchange_wetted(Sinter::State& s, double dt) {
  const SubstrateGeometry& g = s.g;
  for (const auto& w : s.wetted) {
    const std::size_t i = w.particle;
    for (const auto& [column, weight] : w.footprint) {
      if (s.gone[i]) break;  // ablated by an earlier node's heat
      if (weight <= 0) continue;
      const std::size_t node = top_node(s, column);
      const double tp = s.temperature[i], tq = s.node_temperature[node];
      const double path = path_conductance(conductivity_at<Variable>(s, tp),
                                           conductivity_at<Variable>(s, tq), w.shape);
      const double conductance = weight / (1 / path + w.interface);
      const double c_particle = s.mass[i] * secant_capacity(s.per_kg, tp, tq);
      const bool reservoir = g.fixed_column(column);  // Dirichlet nodes
      const double volume = reservoir ? 0 : node_volume(s, node);
      const double c_node = reservoir ? 1e300 : volume * secant_capacity(s.per_m3, tq, tp);
      double energy = exact_exchange(conductance, c_particle, tp, c_node, tq, dt);
      // Neither side beyond the other's temperature (the capacities are secants, not exact).
      double limit = s.mass[i] * std::abs(s.per_kg.enthalpy(tq) - s.h[i]);
      if (!reservoir) limit = std::min(limit, volume * std::abs(s.per_m3.enthalpy(tp) - s.e[node]));
      energy = std::clamp(energy, -limit, limit);
      s.h[i] += energy / s.mass[i];
      particle_enthalpy_changed(s, i);
      if (reservoir) s.ledger.boundary -= energy;
      else s.sources.push_back({node, -energy});
    }
  }
}

}  // namespace

void wetted_exchange(Sinter::State& s, double dt) {
  if (s.scene.has(kVariableProperties)) exchange_wetted<true>(s, dt);
  else exchange_wetted<false>(s, dt);
}

}  // namespace powderbed::thermal

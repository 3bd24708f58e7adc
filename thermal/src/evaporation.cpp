// Evaporation from the exposed particles and from the substrate's surface (evaporation.hpp has
// the law and its sources; docs/physics.md "Evaporation" the model's limits). The loss is
// integrated by linearised backward Euler: over a step dt a body of capacity C losing F(T)
// loses F dt / (1 + F'(T) dt / C), which never overshoots however steep F grows with T (F
// grows like exp(-L_v M / R T)), so evaporation adds no bound to the stable steps.
#include <algorithm>
#include <cmath>
#include <utility>

#include "powderbed/thermal/lit_sphere_surface.hpp"
#include "solver_state.hpp"

namespace powderbed::thermal {

namespace {

// d ln(ṁ)/dT of the Hertz–Knudsen–Langmuir flux: L_v M / (R T²) - 1 / (2T).
double log_flux_slope(const EvaporationParams& p, double t) {
  return p.latent_vapour * p.molar_mass / (kGasConstant * t * t) - 0.5 / t;
}

// Below the melting point the flux is below 1e-4 of its value at the boiling point for the
// shipped metals: not evaluated there.
bool evaporates(const Sinter::State& s, double t) { return t >= s.scene.phase_change.melting_point; }

// Mass that evaporates from area `area` at temperature t over dt from a body of capacity
// `capacity` (J/K), kg.
double evaporated_mass(const Sinter::State& s, double t, double area, double capacity, double dt) {
  const EvaporationParams& p = s.vapour;
  const double flux = evaporation_mass_flux(p, t) * area;  // kg/s
  const double slope = p.latent_vapour * flux * log_flux_slope(p, t);  // dF/dT, W/K
  return flux * dt / (1 + slope * dt / capacity);
}

// Where particle i evaporates and over what area (docs/physics.md "Particles under the beam").
// One at a single temperature (unlit, or wholly liquid: stirred by Marangoni flow, Ma =
// |dγ/dT| ΔT r / (μ κ) ~ 1e5 for 316L at ΔT ~ 1000 K) over its free upper hemisphere 2π r²
// (the lower half faces the bed, where the vapour recondenses on its neighbours). A lit one not
// yet wholly liquid at its lit disc π r², hotter than its mean by the conduction excess of
// lit_sphere_surface.hpp less what evaporates there, and no hotter than its T_d(r) (past it the
// recoil blows the melt off); k and κ of the solid.
struct EvaporatingSurface {
  double temperature, area;
};

EvaporatingSurface evaporating_surface(const Sinter::State& s, std::size_t i) {
  const double t = s.temperature[i], power = s.laser_power[i];
  const PhaseChange& pc = s.scene.phase_change;
  if (power <= 0 || s.lit_time[i] <= 0 || t >= pc.melting_point + 0.5 * pc.window)
    return {t, 2 * s.area[i]};
  const double t_solid = std::min(t, pc.melting_point - 0.5 * pc.window);
  const double k = s.conductivity(t_solid), kappa = k / s.per_m3.capacity(t_solid);
  const double excess =
      lit_surface_excess(power / s.area[i], s.radius[i], k, kappa, s.lit_time[i]);
  const double latent_flux = s.vapour.latent_vapour * s.area[i];
  const double t_s = lit_surface_temperature(t, excess, power, [&](double ts) {
    return latent_flux * evaporation_mass_flux(s.vapour, ts);
  });
  return {std::max(t, std::min(t_s, s.particle_depression_temperature[i])), s.area[i]};
}

}  // namespace

// Takes the mass dm off particle i as vapour carrying h_out per kilogram (its own enthalpy
// plus L_v); what remains holds the rest, (m h - dm h_out) / (m - dm). A particle whose rest
// would count as gone (kVaporisedMass) loses it all, carrying the enthalpy it holds: the latent
// heat of those last crumbs (under 1e-3 of the particle) is not charged, so no energy is made.
// Returns {energy, mass} that left: the drop of m h, exactly.
std::pair<double, double> lose_mass(Sinter::State& s, std::size_t i, double dm, double h_out) {
  const double before = s.mass[i] * s.h[i];
  if (s.mass[i] - dm < kVaporisedMass * s.initial_mass[i]) {  // gone: its peak stays as it was
    dm = s.mass[i];
    s.mass[i] = 0;
    s.gone[i] = 1;
    ++s.gone_count;
    return {before, dm};
  }
  s.h[i] = (before - dm * h_out) / (s.mass[i] - dm);
  s.mass[i] -= dm;
  particle_state_changed(s, i);
  return {before - s.mass[i] * s.h[i], dm};
}

// The exposed particles (evaporating_surface says where and over what): each loses dm, which
// carries its enthalpy and the latent heat L_v.
void evaporate_particles(Sinter::State& s, double dt) {
  const double latent = s.vapour.latent_vapour;
  double energy = 0, mass = 0;
  for (const auto i : s.exposed) {
    s.lit_time[i] = s.laser_power[i] > 0 ? s.lit_time[i] + dt : 0;
    if (s.gone[i]) continue;
    const EvaporatingSurface surface = evaporating_surface(s, i);
    const double t = surface.temperature;
    if (!evaporates(s, t)) continue;
    const double capacity = s.mass[i] * s.per_kg.capacity(s.temperature[i]);
    const double dm = evaporated_mass(s, t, surface.area, capacity, dt);
    s.peak_recoil = std::max(s.peak_recoil, recoil_pressure(s.vapour, t));
    const auto [de, dmass] = lose_mass(s, i, dm, s.h[i] + latent);
    energy += de;
    mass += dmass;
    particle_enthalpy_changed(s, i);
  }
  s.ledger.evaporation -= energy;
  s.evaporated_particles += mass;
}

// The depression on a particle: past T_d(r), where its recoil beats its own capillary pressure
// 2γ/r, the melt is blown off as vapour (vapour_depression.hpp): the enthalpy beyond h(T_d(r))
// evaporates dm = m (h - h_d) / L_v, which leaves with h_d + L_v; what remains sits at T_d(r).
void ablate(Sinter::State& s, std::size_t i) {
  const double h_d = s.particle_depression_enthalpy[i];
  const double latent = s.vapour.latent_vapour;
  const auto [energy, mass] = lose_mass(s, i, s.mass[i] * (s.h[i] - h_d) / latent, h_d + latent);
  s.ledger.evaporation -= energy;
  s.evaporated_particles += mass;
}

// The substrate's surface: per free column (neither Dirichlet nor a periodic seam's image) its surface node (the top node, or the
// depression's wall: surface_node) over the column's area dx dy. The grid keeps its volume
// (the evaporated mass, booked, is below a percent of a cell's), so the energy lost is L_v dm.
// Taken from the nodes' enthalpies at once (the grid step's conduction reads temperatures), so
// the depression's drill() sees the loss when it fills the surface to T_d.
void evaporate_surface(Sinter::State& s, double dt) {
  const SubstrateGeometry& g = s.g;
  const double latent = s.vapour.latent_vapour, area = g.dx * g.dy;
  double energy = 0, mass = 0;
  for (std::size_t c = 0; c < g.columns(); ++c) {
    if (!evaporates(s, s.node_temperature[top_node(s, c)]) || g.fixed_column(c) || g.image_column(c))
      continue;
    const std::size_t node = surface_node(s, c);
    const double t = s.node_temperature[node];
    if (!evaporates(s, t)) continue;
    const double capacity = node_volume(s, node) * s.per_m3.capacity(t);
    const double dm = evaporated_mass(s, t, area, capacity, dt);
    s.peak_recoil = std::max(s.peak_recoil, recoil_pressure(s.vapour, t));
    s.e[node] -= latent * dm / node_volume(s, node);
    energy += latent * dm;
    mass += dm;
  }
  s.ledger.evaporation -= energy;
  s.evaporated_substrate += mass;
}

}  // namespace powderbed::thermal

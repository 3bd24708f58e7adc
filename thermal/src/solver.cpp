#include "powderbed/thermal/solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/sphere_volume.hpp"
#include "powderbed/thermal/beer_lambert_laser.hpp"
#include "powderbed/thermal/contact_conduction.hpp"
#include "powderbed/thermal/melt_pool.hpp"
#include "powderbed/thermal/vapour_depression.hpp"
#include "solver_state.hpp"

namespace powderbed::thermal {

namespace {

// The enthalpy and conductivity tables span from below T0 to far past vaporisation.
double table_low(const SinterScene& s) {
  return 0.5 * std::min(s.initial_temperature, s.environment_temperature);
}
double table_high(const SinterScene& s) {
  return s.phase_change.boiling_point + s.phase_change.window + 5000;
}

// The material with the scene's effects applied: properties held at T0 without
// variable-properties, no latent heat without phase-change.
Material scene_material(const SinterScene& scene, const MaterialTable& table) {
  PhaseChange phase = scene.phase_change;
  if (!scene.has(kPhaseChange)) phase.latent_melt = phase.latent_vapour = 0;
  // With evaporation L_v leaves with the evaporated mass (evaporation.cpp), not at T_v.
  if (scene.has(kEvaporation)) phase.latent_vapour = 0;
  if (scene.has(kVariableProperties))
    return Material(table, phase, scene.hold_from, scene.liquid_conductivity);
  const Material full(table, scene.phase_change, scene.hold_from, scene.liquid_conductivity);
  const double t0 = scene.initial_temperature;
  MaterialTable constant;
  constant.temperature = {t0 - 1, t0};
  constant.specific_heat.assign(2, full.solid_specific_heat(t0));
  constant.conductivity.assign(2, full.solid_conductivity(t0));
  constant.density.assign(2, full.solid_density(t0));
  constant.liquid_specific_heat = constant.specific_heat[0];
  constant.liquid_conductivity = constant.conductivity[0];
  constant.liquid_density = constant.density[0];
  return Material(constant, phase, t0, LiquidConductivity::table);
}

[[noreturn]] void refuse_bed(const std::string& what) {
  throw InputError("--bed: " + what);
}

// docs/physics.md §5: the bed rests on the substrate's top face, which is the bed domain's floor (or on
// the solid raised above it).
void check_bed(const bed::Bed& bed, const SubstrateGeometry& g, const TopHeight& top) {
  if (bed.domain.dimension != 3) refuse_bed("a 2D bed (accepted: a 3D bed)");
  const double floor = bed.domain.lower[2];
  double lowest_bottom = std::numeric_limits<double>::infinity();
  double smallest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < bed.n(); ++i) {
    if (bed.z[i] <= floor) {
      refuse_bed(fmt::format(
          "particle {} has its centre at z = {:g} m, at or below the substrate plane z = {:g} m "
          "(accepted: every centre above the bed domain's floor)",
          bed.id[i], bed.z[i], floor));
    }
    lowest_bottom = std::min(lowest_bottom, bed.z[i] - bed.radius[i] -
                                                (top_height_at(g, top, bed.x[i], bed.y[i]) - floor));
    smallest = std::min(smallest, bed.radius[i]);
  }
  // A bed that floats (e.g. packed in a box whose floor is not the substrate) has no substrate
  // plane under it; a settled bed touches its floor within round-off of its smallest particle.
  if (bed.n() > 0 && lowest_bottom - floor > 0.01 * smallest) {
    refuse_bed(fmt::format(
        "the lowest particle's bottom is at z = {:g} m, above the substrate plane z = {:g} m (the "
        "domain floor): no particle rests on the substrate (accepted: a bed settled on its "
        "floor, e.g. from deposit)",
        lowest_bottom, floor));
  }
}

// The planes over the plate a part may fill in this run: up to the raised top's highest column
// and, where wetting merges molten particles into the pool, up to the bed's highest particle
// (a merged particle's volume stays under the top it had). The explicit integrator only (the
// implicit one refuses a raised top; a merge there lumps into the plate's top node).
std::size_t planes_above(const bed::Bed& bed, const SinterScene& scene, const TopHeight& top,
                         double z_top, double dz) {
  if (scene.integrator != Integrator::explicit_euler) return 0;
  double highest = z_top;
  for (const double h : top) highest = std::max(highest, h);
  if (scene.has(kWetting))
    for (std::size_t i = 0; i < bed.n(); ++i) highest = std::max(highest, bed.z[i] + bed.radius[i]);
  return static_cast<std::size_t>(std::ceil((highest - z_top) / dz - 1e-9));
}

SubstrateGeometry make_grid(const bed::Bed& bed, const SinterScene& scene, const TopHeight& top) {
  SubstrateGeometry g;
  g.nx = scene.nodes[0];
  g.ny = scene.nodes[1];
  g.x0 = bed.domain.lower[0];
  g.y0 = bed.domain.lower[1];
  g.z_top = bed.domain.lower[2];
  g.dx = bed.domain.length(0) / static_cast<double>(g.nx - 1);
  g.dy = bed.domain.length(1) / static_cast<double>(g.ny - 1);
  g.dz = scene.substrate_depth / static_cast<double>(scene.nodes[2] - 1);
  g.periodic_y = scene.periodic_y;
  if (g.periodic_y && !bed.domain.periodic[1])
    throw InputError("substrate.periodic: y on a bed bounded along y (accepted: a bed periodic "
                     "along y, or substrate.periodic = none)");
  g.nz_above = planes_above(bed, scene, top, g.z_top, g.dz);
  g.nz = scene.nodes[2] + g.nz_above;
  return g;
}

// Forward-Euler bounds (Gershgorin): dt <= C / Σ G per node and per particle, with the
// smallest capacity over the temperatures a run can reach and the largest conductivity any
// neighbour can have, so the bound holds in every state.
// The hottest state the bounds consider: vaporisation, or with evaporation (no particle leaves
// at a temperature) the top of the property tables.
double hottest_state(const Sinter::State& s) {
  return std::min(s.vaporised_temperature, table_high(s.scene));
}

double max_conductivity(const Sinter::State& s) {
  double k_max = 0;
  for (double t = s.scene.initial_temperature; t <= hottest_state(s); t += 0.25)
    k_max = std::max(k_max, s.conductivity(t));
  return k_max;
}

StableSteps compute_stable_steps(const Sinter::State& s) {
  StableSteps out;
  const SubstrateGeometry& g = s.g;
  const double t_lo = s.scene.initial_temperature, t_hi = hottest_state(s);
  const double k_max = s.k_max;
  double capacity_over_k = std::numeric_limits<double>::infinity();
  for (double t = t_lo; t <= t_hi; t += 0.25) {
    const double face_k = 0.5 * (s.conductivity(t) + k_max);
    capacity_over_k = std::min(capacity_over_k, s.per_m3.capacity(t) / face_k);
  }
  const double stencil = 2 * (1 / (g.dx * g.dx) + 1 / (g.dy * g.dy) + 1 / (g.dz * g.dz));
  out.grid = capacity_over_k / stencil;
  out.grid_node = g.index(g.nx / 2, g.ny / 2, g.nz / 2);
  // Top nodes carry particle contacts too: C = (rho c)_min V/2, Σ G adds k_max A/h w.
  const double rho_c_min = s.per_m3.min_capacity();
  // (A raised top's thicker top nodes have more capacity and, against it, conductances that grow
  // no faster: the flat top's bound holds for them.)
  std::vector<double> contact(g.columns(), 0.0);
  for (const auto& c : s.net.substrate)
    for (int w = 0; w < 4; ++w) contact[c.stencil.column[w]] += c.stencil.weight[w] * k_max * c.shape;
  const double grid_g = k_max * (g.dy * g.dz / g.dx + g.dx * g.dz / g.dy + g.dx * g.dy / g.dz);
  for (const auto& c : s.net.substrate) {
    for (const auto column : c.stencil.column) {
      const double bound = rho_c_min * 0.5 * g.cell_volume() / (grid_g + contact[column]);
      if (bound < out.grid) {
        out.grid = bound;
        out.grid_node = top_node(s, column);
      }
    }
  }
  // Particles: m c_min / (Σ contacts k_max shape + h A + 4 eps sigma T^3 A).
  out.particle = std::numeric_limits<double>::infinity();
  std::vector<double> conductance(s.x.size(), 0.0);
  if (s.scene.has(kConduction))
    for (const auto& p : s.net.pairs) {
      conductance[p.i] += k_max * p.shape;
      conductance[p.j] += k_max * p.shape;
    }
  if (s.scene.has(kSubstrateContact))
    for (const auto& c : s.net.substrate) conductance[c.particle] += k_max * c.shape;
  for (const auto i : s.exposed) {
    if (s.scene.has(kConvection)) conductance[i] += s.environment.convection * s.area[i];
    if (s.scene.has(kRadiation)) conductance[i] += radiation_conductance(s.environment, t_hi, s.area[i]);
  }
  const double c_min = s.per_kg.min_capacity();
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    if (conductance[i] <= 0) continue;
    const double bound = s.mass[i] * c_min / conductance[i];
    if (bound < out.particle) {
      out.particle = bound;
      out.particle_index = i;
    }
  }
  return out;
}

}  // namespace

// The state's enthalpies are measured from T0.
std::pair<double, double> internal_energy(const Sinter::State& s) {
  double particles = 0;
  for (std::size_t i = 0; i < s.x.size(); ++i) particles += s.mass[i] * s.h[i];
  double substrate = 0;
  const SubstrateGeometry& g = s.g;
  for (std::size_t k = 1; k < g.nz; ++k)
    for (std::size_t j = g.first_row(); j + 1 < g.ny; ++j)
      for (std::size_t i = 1; i + 1 < g.nx; ++i) {
        const std::size_t c = g.index(i, j, k);
        substrate += node_volume(s, c) * s.e[c];
      }
  return {particles, substrate};
}


double EnergyLedger::relative_error() const {
  const double in = absorbed() + convection + radiation + evaporation;
  const double out = internal_particles + internal_substrate + boundary;
  const double scale = std::max({std::abs(absorbed()), std::abs(in), std::abs(out)});
  return scale > 0 ? std::abs(in - out) / scale : 0.0;
}

Sinter::State::State(const SinterScene& sc, Material m)
    : scene(sc),
      material(std::move(m)),
      per_kg(material, EnthalpyCurve::Per::kilogram, sc.initial_temperature, table_low(sc),
             table_high(sc)),
      per_m3(material, EnthalpyCurve::Per::cubic_metre, sc.initial_temperature, table_low(sc),
             table_high(sc)),
      conductivity([this](double t) { return material.conductivity(t); }, table_low(sc),
                   table_high(sc), std::min(1.0, sc.phase_change.window / 8)),
      capacity_per_kg([this](double t) { return per_kg.capacity(t); }, table_low(sc),
                      table_high(sc), std::min(1.0, sc.phase_change.window / 8)),
      capacity_per_m3([this](double t) { return per_m3.capacity(t); }, table_low(sc),
                      table_high(sc), std::min(1.0, sc.phase_change.window / 8)) {}

namespace {

// The laser's path, checked against the bed: the scene's scan path, or its single track along
// x, and t_end.
void setup_track(Sinter::State& s, const bed::Bed& bed) {
  const SinterScene& scene = s.scene;
  const SubstrateGeometry& g = s.g;
  const double lx = bed.domain.length(0), ly = bed.domain.length(1);
  if (!scene.scan_path.empty()) {
    check_scan_path(scene.scan_path, scene.jump_speed, g.x0, g.x0 + lx, g.y0, g.y0 + ly);
    s.schedule = ScanSchedule(scene.scan_path, scene.jump_speed);
    s.t_end = std::isnan(scene.t_end) ? s.schedule.finish() : scene.t_end;
    return;
  }
  const double laser_y = std::isnan(scene.laser_y) ? g.y0 + 0.5 * ly : scene.laser_y;
  const double start_x = std::isnan(scene.start_x) ? g.x0 - scene.spot_radius : scene.start_x;
  const double end_x = std::isnan(scene.end_x) ? g.x0 + lx + scene.spot_radius : scene.end_x;
  if (!(laser_y >= g.y0 && laser_y <= g.y0 + ly)) {
    throw InputError(
        fmt::format("laser.y: {:g} m is outside the bed (accepted: {:g} to {:g} m)", laser_y,
                    g.y0, g.y0 + ly));
  }
  if (!(end_x > start_x && end_x > g.x0 && start_x < g.x0 + lx)) {
    throw InputError(fmt::format(
        "laser.start-x, laser.end-x: {:g} to {:g} m never crosses the bed (accepted: start < "
        "end, overlapping {:g} to {:g} m)",
        start_x, end_x, g.x0, g.x0 + lx));
  }
  s.t_end = std::isnan(scene.t_end) ? (end_x - start_x) / scene.speed : scene.t_end;
  // A t_end past the track's end keeps the beam moving along its line (as the single track
  // always did): the segment runs to t_end, a hair longer so that every step is on it.
  const double run = std::max(end_x - start_x, scene.speed * s.t_end) * (1 + 1e-9);
  s.schedule = ScanSchedule({{start_x, laser_y, start_x + run, laser_y, scene.power, scene.speed}},
                            scene.jump_speed);
}

// Vaporisation: past T_v's window, or with evaporation when a particle's mass has evaporated;
// the vapour's parameters and the depression's temperature T_d.
void setup_vapour(Sinter::State& s) {
  const SinterScene& scene = s.scene;
  s.vaporised_temperature = scene.has(kEvaporation)
                                ? std::numeric_limits<double>::infinity()
                                : scene.phase_change.boiling_point + 0.5 * scene.phase_change.window;
  s.vapour = {scene.phase_change.boiling_point, scene.phase_change.latent_vapour, scene.molar_mass,
              scene.ambient_pressure, scene.back_condensation};
  s.depression_temperature =
      scene.has(kDepression)
          ? depression_temperature(s.vapour, scene.surface_tension, scene.spot_radius)
          : std::numeric_limits<double>::infinity();
  s.particle_depression_temperature.assign(s.x.size(), std::numeric_limits<double>::infinity());
  s.particle_depression_enthalpy.assign(s.x.size(), std::numeric_limits<double>::infinity());
  if (!scene.has(kDepression)) return;
  s.particle_depression_temperature.clear();
  s.particle_depression_enthalpy.clear();
  for (const double r : s.radius) {
    const double t_d = depression_temperature(s.vapour, scene.surface_tension, r);
    s.particle_depression_temperature.push_back(t_d);
    s.particle_depression_enthalpy.push_back(s.per_kg.enthalpy(t_d));
  }
}

// Particles at T0: positions, masses, projected areas, Beer–Lambert factors, exposure.
void setup_particles(Sinter::State& s, const bed::Bed& bed) {
  const std::size_t n = bed.n();
  const double t0 = s.scene.initial_temperature;
  s.x = bed.x;
  s.y = bed.y;
  s.z = bed.z;
  s.radius = bed.radius;
  s.mass.resize(n);
  s.area.resize(n);
  s.laser_factor.resize(n);
  const double rho0 = s.material.density(t0);
  for (std::size_t i = 0; i < n; ++i) {
    const double r = bed.radius[i];
    s.mass[i] = rho0 * bed::sphere_volume(r);
    s.area[i] = M_PI * r * r;
    s.laser_factor[i] =
        particle_laser_factor(s.scene.absorptivity, s.area[i], s.beta, s.surface.depth[i]);
    if (s.surface.exposed[i]) s.exposed.push_back(static_cast<std::uint32_t>(i));
  }
  s.h.assign(n, 0.0);  // enthalpies are measured from T0
  s.temperature.assign(n, t0);
  s.peak.assign(n, t0);
  s.heat.assign(n, 0.0);
  s.laser_power.assign(n, 0.0);
  s.lit_time.assign(n, 0.0);
  s.gone.assign(n, 0);
  s.initial_mass = s.mass;
}

// Substrate nodes at T0 and the Beer–Lambert transmission above each top node (1 without
// penetration or particles).
void setup_substrate(Sinter::State& s) {
  const SubstrateGeometry& g = s.g;
  const double t0 = s.scene.initial_temperature;
  s.e.assign(g.size(), 0.0);
  s.node_temperature.assign(g.size(), t0);
  s.node_peak.assign(g.size(), t0);
  s.node_max = t0;
  s.transmission.assign(g.nx * g.ny, 1.0);
  for (std::size_t j = 0; j < g.ny; ++j) {
    for (std::size_t i = 0; i < g.nx; ++i) {
      const double above = s.scene.substrate_shading == SubstrateShading::layer
                               ? s.layer_height
                               : s.surface.column_height(g.x(i), g.y(j));
      s.transmission[i + g.nx * j] = beer_lambert_transmission(s.beta, above);
    }
  }
  s.k_fixed = s.material.conductivity(t0);
  s.node_k.assign(g.size(), s.k_fixed);
  if (s.scene.has(kDepression)) s.column_energy.assign(g.nx * g.ny, 0.0);
}

// The grid step (the user's, checked against the bound, or safety x the bound) and the particle
// substeps within it.
void choose_steps(Sinter::State& s) {
  const SinterScene& scene = s.scene;
  s.k_max = max_conductivity(s);
  s.stable = compute_stable_steps(s);
  const double bound = s.stable.grid;
  if (scene.dt > 0) {
    if (scene.integrator == Integrator::explicit_euler && scene.dt > bound && !scene.unsafe_dt) {
      throw InputError(fmt::format(
          "--dt: {:g} s is above the forward-Euler stable bound {:g} s of the substrate grid "
          "(accepted: dt <= {:g} s, --unsafe-dt, or --integrator implicit)",
          scene.dt, bound, bound));
    }
    s.dt = scene.dt;
  } else {
    s.dt = scene.integrator == Integrator::explicit_euler
               ? scene.safety * bound
               : scene.spot_radius / (20 * scene.speed);  // the beam moves w/20 per step
  }
  s.dt = std::min(s.dt, s.t_end);
  // Particle step: the stable bound, and the accuracy limit of the laser's heating rate
  // (alpha I0 A_i / (m_i c_min) at the beam's peak) for particles the track can reach.
  double particle_dt = scene.safety * s.stable.particle;
  // (Ray tracing sets this limit from each traced map as the beam moves: prepare_traces.)
  // Particles within the beam's reach of a segment's line (the whole line: a bound, not a
  // trajectory), at that segment's power.
  for (std::size_t m = 0; m < s.schedule.segments().size() && scene.has(kLaser) && !s.tracer; ++m) {
    const ScanSegment& seg = s.schedule.segments()[m];
    if (!(seg.power > 0)) continue;
    const auto d = s.schedule.direction(m);
    const double i0 = peak_intensity(laser_with_power(s, seg.power)), c_min = s.per_kg.min_capacity();
    const double reach = std::sqrt(kBeamCutoff2) * scene.spot_radius;
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (std::abs((s.x[i] - seg.x0) * d[1] - (s.y[i] - seg.y0) * d[0]) > reach) continue;
      const double rate = s.laser_factor[i] * i0 / (s.mass[i] * c_min);
      particle_dt = std::min(particle_dt, scene.max_particle_rise / rate);
    }
  }
  if (scene.integrator == Integrator::explicit_euler && std::isfinite(particle_dt))
    s.substeps = static_cast<std::size_t>(std::ceil(s.dt / particle_dt));
  s.substeps_stable = s.substeps;  // the traced maps and wetting may raise it, never lower it
}

}  // namespace

namespace {

// A raised top: one height per column, none below z_top.
void setup_top(Sinter::State& s, TopHeight top) {
  const SubstrateGeometry& g = s.g;
  if (top.empty()) {
    set_top_planes(s);
    return;
  }
  if (top.size() != g.nx * g.ny) {
    throw InputError(fmt::format(
        "solid top: {} column heights for a grid of {} x {} top nodes (accepted: one height per "
        "top node)",
        top.size(), g.nx, g.ny));
  }
  for (std::size_t c = 0; c < top.size(); ++c) {
    if (!(top[c] >= g.z_top) || !std::isfinite(top[c])) {
      throw InputError(fmt::format(
          "solid top: column {} at z = {:g} m, below the plate's top {:g} m (accepted: heights "
          ">= the bed domain's floor)",
          c, top[c], g.z_top));
    }
  }
  if (s.scene.integrator != Integrator::explicit_euler)
    throw InputError("solid top: a raised top works with --integrator explicit only (accepted: "
                     "--integrator explicit)");
  s.top = std::move(top);
  set_top_planes(s);
}

}  // namespace

void set_top_planes(Sinter::State& s) {
  const SubstrateGeometry& g = s.g;
  s.top_plane.assign(g.columns(), static_cast<std::uint32_t>(g.k_plate()));
  s.top_thickness.assign(g.columns(), 0.5);
  for (std::size_t c = 0; c < s.top.size(); ++c) {
    // In planes; a height a whole number of planes up within round-off (3 x 4e-6 / 4e-6 is
    // 2.9999999999999996) is that plane's, not a node 1.5 dz thick under it.
    const double rise = (s.top[c] - g.z_top) / g.dz;
    const double above = std::min(std::floor(rise + 1e-9), static_cast<double>(g.nz_above));
    s.top_plane[c] = static_cast<std::uint32_t>(g.k_plate() + static_cast<std::size_t>(above));
    s.top_thickness[c] = 0.5 + (rise - above);
  }
  s.highest_plane = *std::max_element(s.top_plane.begin(), s.top_plane.end());
}

void raise_column(Sinter::State& s, std::size_t column, double rise) {
  const SubstrateGeometry& g = s.g;
  if (s.top.empty()) s.top.assign(g.columns(), g.z_top);
  s.top[column] += rise;
  s.top_thickness[column] += rise / g.dz;
  while (s.top_thickness[column] >= 1.5 && s.top_plane[column] + 1 < g.nz) {
    const std::size_t below = top_node(s, column), above = below + g.columns();
    s.e[above] = s.e[below];
    s.node_temperature[above] = s.node_temperature[below];
    s.node_k[above] = s.node_k[below];
    s.node_peak[above] = s.node_temperature[below];
    ++s.top_plane[column];
    s.top_thickness[column] -= 1;
  }
  s.highest_plane = std::max<std::size_t>(s.highest_plane, s.top_plane[column]);
}

Sinter::Sinter(const bed::Bed& bed, const SinterScene& scene, const MaterialTable& table)
    : Sinter(bed, scene, table, TopHeight{}) {}

Sinter::Sinter(const bed::Bed& bed, const SinterScene& scene, const MaterialTable& table,
               TopHeight top) {
  scene.validate();
  s_ = std::make_unique<State>(scene, scene_material(scene, table));
  State& s = *s_;
  s.g = make_grid(bed, scene, top);
  setup_top(s, std::move(top));
  check_bed(bed, s.g, s.top);
  setup_track(s, bed);
  s.surface = analyse_surface(bed, s.g.z_top);
  s.net = build_network(bed, s.g, s.top);
  s.layer_height = s.surface.layer_height;
  s.beta = bed.n() > 0 && scene.has(kPenetration)
               ? gusarov_extinction(s.surface.porosity, s.surface.mean_diameter)
               : 0.0;
  s.laser = {scene.power, scene.spot_radius, scene.absorptivity, s.beta};
  s.environment = {scene.convection, scene.emissivity, scene.environment_temperature};
  setup_particles(s, bed);
  setup_vapour(s);
  setup_substrate(s);
  setup_laser(s, bed);
  copy_image_row(s);  // a raised top's image row may differ from row 0 in the last bit
  if (scene.has(kWetting)) setup_wetting(s);
  choose_steps(s);
  setup_tracks(s);
}

Sinter::~Sinter() = default;

void check_finite(const Sinter::State& s, bool grid) {
  for (std::size_t i = 0; i < s.temperature.size(); ++i) {
    if (!std::isfinite(s.temperature[i])) {
      throw NumericalError(fmt::format(
          "particle {} reached a non-finite temperature at step {} (t = {:g} s); the time step "
          "is beyond the stable bound",
          i, s.step, s.time));
    }
  }
  if (!grid) return;
  double peak = 0;
  for (const double t : s.node_temperature) peak = std::max(peak, std::isfinite(t) ? t : INFINITY);
  if (std::isfinite(peak)) return;
  for (std::size_t c = 0; c < s.node_temperature.size(); ++c) {
    if (std::isfinite(s.node_temperature[c])) continue;
    const SubstrateGeometry& g = s.g;
    throw NumericalError(fmt::format(
        "substrate node ({}, {}, {}) reached a non-finite temperature at step {} (t = {:g} s); "
        "the time step is beyond the stable bound",
        c % g.nx, (c / g.nx) % g.ny, c / (g.nx * g.ny), s.step, s.time));
  }
}

SinterResult Sinter::run(const std::function<void(const Sinter&)>& snapshot, std::uint64_t every,
                         const std::function<void(const SinterProgress&)>& progress) {
  State& s = *s_;
  // Measured from here, not from T0: a test may start particles or nodes elsewhere.
  const auto [particles_start, substrate_start] = internal_energy(s);
  const auto started = std::chrono::steady_clock::now();
  auto last_report = started;
  if (snapshot) snapshot(*this);
  const double t_end = s.t_end;
  while (s.time < t_end * (1 - 1e-12)) {
    const double dt = std::min(s.dt, t_end - s.time);
    if (s.scene.integrator == Integrator::explicit_euler) explicit_step(s, dt);
    else implicit_step(s, dt);
    s.time += dt;
    ++s.step;
    // Cheap watch on the particles every step (so a failure names its step); the grid every 64
    // steps and at the end.
    check_finite(s, s.step % 64 == 0 || s.time >= t_end * (1 - 1e-12));
    watch_tracks(s);
    if (snapshot && every > 0 && s.step % every == 0) snapshot(*this);
    const auto now = std::chrono::steady_clock::now();
    if (progress && now - last_report > std::chrono::seconds(1)) {
      last_report = now;
      progress({s.time, t_end, peak_temperatures(s), s.step});
    }
  }
  check_finite(s);
  if (snapshot && (every == 0 || s.step % every != 0)) snapshot(*this);

  return summarise(s, particles_start, substrate_start);
}

const StableSteps& Sinter::stable_steps() const { return s_->stable; }
double Sinter::dt() const { return s_->dt; }
std::size_t Sinter::substeps() const { return s_->substeps; }
double Sinter::t_end() const { return s_->t_end; }
const SubstrateGeometry& Sinter::grid() const { return s_->g; }
const std::vector<ScanSegment>& Sinter::scan_path() const { return s_->schedule.segments(); }
const TopHeight& Sinter::top_height() const { return s_->top; }
const SinterScene& Sinter::scene() const { return s_->scene; }
const std::vector<double>& Sinter::particle_mass() const { return s_->mass; }
const std::vector<std::uint8_t>& Sinter::particle_merged() const { return s_->merged; }
const std::vector<std::uint32_t>& Sinter::particle_coalesced_into() const {
  return s_->coalesced_into;
}
const std::vector<double>& Sinter::particle_z() const { return s_->z; }
const std::vector<double>& Sinter::particle_radius() const { return s_->radius; }
const BedSurface& Sinter::surface() const { return s_->surface; }
const ConductionNetwork& Sinter::network() const { return s_->net; }
const Material& Sinter::material() const { return s_->material; }
double Sinter::extinction() const { return s_->beta; }
double Sinter::absorptance_at(double x) const {
  return absorbed_fraction(*s_, x, s_->schedule.segments().front().y0);
}
double Sinter::time() const { return s_->time; }
std::uint64_t Sinter::step() const { return s_->step; }
const std::vector<double>& Sinter::particle_temperature() const { return s_->temperature; }
const std::vector<double>& Sinter::particle_max_temperature() const { return s_->peak; }
const std::vector<double>& Sinter::substrate_temperature() const {
  return s_->node_temperature;
}
const std::vector<double>& Sinter::substrate_peak() const { return s_->node_peak; }
const std::vector<std::uint32_t>& Sinter::top_planes() const { return s_->top_plane; }

std::vector<std::uint8_t> Sinter::particle_phase() const {
  std::vector<std::uint8_t> phase(s_->x.size());
  for (std::size_t i = 0; i < phase.size(); ++i)
    phase[i] = s_->gone[i] && !merged_away(*s_, i)
                   ? 2
                   : static_cast<std::uint8_t>(std::min(
                                     s_->material.phase(s_->temperature[i]),
                                     s_->scene.has(kEvaporation) ? 1u : 2u));
  return phase;
}

void Sinter::set_particle_temperature(std::size_t i, double t) {
  s_->temperature.at(i) = t;
  s_->h[i] = s_->per_kg.enthalpy(t);
  s_->peak[i] = std::max(s_->peak[i], t);
}

void Sinter::set_substrate_temperature(std::size_t node, double t) {
  State& s = *s_;
  const SubstrateGeometry& g = s.g;
  const std::size_t plane = g.columns();  // an image node is its row-0 node
  node = g.canonical_column(node % plane) + plane * (node / plane);
  if (g.fixed(node % g.nx, (node / g.nx) % g.ny, node / (g.nx * g.ny))) {
    // A Dirichlet node: its value is a boundary condition, not state.
    s.node_temperature.at(node) = t;
  } else {
    s.node_temperature.at(node) = t;
    s.e[node] = s.per_m3.enthalpy(t);
  }
  s.node_k[node] = s.conductivity(t);
  s.node_peak[node] = std::max(s.node_peak[node], t);
  s.node_max = std::max(s.node_max, t);
}

}  // namespace powderbed::thermal

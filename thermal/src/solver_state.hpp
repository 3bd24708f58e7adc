#pragma once
// The solver's state (private to libthermal): what setup computes once and the steps update.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "powderbed/thermal/beer_lambert_laser.hpp"
#include "powderbed/thermal/evaporation.hpp"
#include "powderbed/thermal/ray_traced_laser.hpp"
#include "powderbed/thermal/solver.hpp"
#include "powderbed/thermal/surface_losses.hpp"

namespace powderbed::thermal {

// The implicit integrator's matrix and solver, built on its first step (implicit_step.cpp).
struct ImplicitSystem;
struct ImplicitSystemDeleter {
  void operator()(ImplicitSystem* p) const;
};

struct Sinter::State {
  SinterScene scene;
  Material material;
  EnthalpyCurve per_kg, per_m3;  // particles: h (J/kg); nodes: e (J/m^3)
  UniformTable conductivity;
  UniformTable capacity_per_kg, capacity_per_m3;  // c(T) and rho c(T) for the implicit matrix
  SubstrateGeometry g;
  BedSurface surface;
  ConductionNetwork net;
  LaserParams laser{};
  SurfaceParams environment{};
  double beta = 0, layer_height = 0, t_end = 0;
  ScanSchedule schedule;  // the laser's path: the scene's single track or its scan path
  double vaporised_temperature = 0;  // T_v + ΔT/2: beyond it a particle has left the bed
  // Evaporation and the depression (evaporation.hpp, vapour_depression.hpp): the vapour's
  // parameters, T_d (infinite without the depression), the mass each particle started with (a
  // particle whose mass has evaporated below kVaporisedMass of it has left the bed), the peak
  // recoil pressure.
  EvaporationParams vapour{};
  double depression_temperature = 0;
  std::vector<double> initial_mass;
  // The depression: per particle T_d(r) (recoil against 2γ/r; infinite without the depression)
  // and its specific enthalpy.
  std::vector<double> particle_depression_temperature, particle_depression_enthalpy;
  double peak_recoil = 0, depression_depth = 0;
  std::vector<double> column_energy;  // the depression: laser energy per top-face column, J
  std::vector<std::uint32_t> touched_columns;  // those with energy this step
  double evaporated_particles = 0, evaporated_substrate = 0;  // kg

  // Particles (structure of arrays).
  std::vector<double> x, y, z, radius, mass, area, laser_factor;
  std::vector<double> h, temperature, peak, heat;  // heat: W, scratch of one step
  // The laser's power into each particle at the last particle step (W) and how long it has
  // been lit without a break (s): the lit surface's excess (lit_sphere_surface.hpp).
  std::vector<double> laser_power, lit_time;
  std::vector<std::uint8_t> gone;                  // vapour, pool or drop: out of the network
  std::vector<std::uint32_t> exposed;

  // Substrate nodes.
  std::vector<double> e, node_temperature, node_k;
  // A raised top (fusion): the column heights (empty while the top is flat). Per column, its
  // top node's plane (nodes above it are empty and never updated) and that node's thickness
  // over dz, (dz/2 + δ)/dz with δ = height - z(plane) in [0, dz) while planes are left (the
  // last plane lumps the rest); flat: the plate's plane and 1/2.
  TopHeight top;
  std::vector<std::uint32_t> top_plane;
  std::vector<double> top_thickness;
  std::size_t highest_plane = 0;  // the largest of top_plane: the grid step's planes end there
  std::vector<double> transmission;  // per top-face node (i + nx j): laser fraction that arrives
  std::vector<double> node_peak;  // peak T of every node (T0 while empty)
  double node_max = 0;            // highest node temperature so far
  struct Source {
    std::size_t node;
    double energy;  // J over the current grid step
  };
  std::vector<Source> sources;  // laser and particle contacts into free top nodes
  std::vector<double> plane_sums;  // scratch of the boundary-flux sum, one per z plane
  double k_fixed = 0;  // conductivity of the Dirichlet nodes (at T0)

  // The laser model, chosen once at start (laser_sources.cpp): power into the particles at time
  // t (added to q, returns the watts absorbed) and energy onto the top nodes over [t, t + dt].
  double (*particle_laser)(Sinter::State&, double t, std::vector<double>& q) = nullptr;
  void (*substrate_laser)(Sinter::State&, double t, double dt) = nullptr;
  // Ray-traced laser: the tracer, the power maps of the traced beam positions around the beam
  // (k trace_spacing from the start of segment m, keyed trace_key(m, k)), the absorptivity of
  // each particle and top node by phase.
  std::unique_ptr<BeamTracer> tracer;
  struct TracedBeam {
    std::uint64_t k;
    AbsorptionMap map;
  };
  std::vector<TracedBeam> traced;
  double trace_spacing = 0;
  TraceSurfaces surfaces;  // the phases and the depression the next trace sees
  std::size_t gone_count = 0, gone_traced = 0;  // particles gone (vapour, pool, drops); as traced
  TraceSummary traces;

  // Wetting (wetting.cpp): per particle, whether it was molten at the last check, its pairs
  // (indices into net.pairs) and its substrate contact (index into net.substrate, -1: none);
  // the substrate contacts that have spread, exchanged exactly once per grid step.
  std::vector<std::uint8_t> molten;
  std::vector<std::vector<std::uint32_t>> pairs_of;
  std::vector<std::int64_t> substrate_of;
  struct WettedContact {
    std::uint32_t particle;
    double shape;  // A / z_c of the cap's base area on the plate, m
    double interface;  // 1 / (h_c A) of an arrested contact, K/W (0: spread on remelted solid)
    std::vector<std::pair<std::size_t, double>> footprint;  // top nodes under the cap, weights
    // Not a cap: a contact with a particle that merged into the pool, or with plate that caps
    // had wetted already (its conductance the contact's, its footprint the cap's it lacked).
    bool through_pool = false;
  };
  std::vector<WettedContact> wetted;
  // Particles wholly molten on remelted solid that have merged into the pool (wetting.cpp):
  // out of every loop as the vaporised are (gone), their enthalpy handed to the nodes under
  // them, their mass kept for fusion.
  std::vector<std::uint8_t> merged;
  std::size_t merged_count = 0;
  // Molten particles that coalesced into a molten neighbour (coalescence.cpp): per particle the
  // drop that took its mass and enthalpy (itself while it has not), and how many did.
  std::vector<std::uint32_t> coalesced_into;
  std::size_t coalesced_count = 0;
  std::vector<double> unwetted_area;  // per top-face column, m^2: what caps have not wetted
  std::size_t arrested = 0;           // wetted contacts still arrested
  std::size_t bridges = 0;  // pairs whose bridge has grown
  std::vector<std::uint32_t> arrested_pairs;  // molten on solid it does not remelt (wetting.cpp)
  double k_max = 0;  // largest conductivity a run can reach (stability bounds)

  // Per-track statistics (track_stats.cpp): for each segment, its midpoint cross-section
  // (top-face columns, their coordinate along the plane) and its centre line (sample points);
  // the window being measured, its section peaks (samples × nz) and particle peaks, and their
  // values when it opened.
  struct TrackProbe {
    std::vector<std::size_t> columns;
    std::vector<double> across;
    std::vector<std::array<double, 2>> line;
    double line_step = 0;
  };
  std::vector<TrackProbe> probes;
  std::size_t track = 0;  // the window being measured
  std::vector<double> section_peak, track_particle_peak;
  std::vector<double> section_start, track_particle_start;  // at the window's start
  std::vector<std::uint8_t> line_molten;  // scratch: centre-line samples molten now
  TrackStats current;
  std::vector<TrackStats> tracks;

  StableSteps stable;
  double dt = 0;
  std::size_t substeps = 1;
  std::size_t substeps_stable = 1;  // what the particles' stable bound alone asks for
  EnergyLedger ledger;
  double time = 0;
  std::uint64_t step = 0, particle_steps = 0;
  std::size_t implicit_iterations = 0;
  std::unique_ptr<ImplicitSystem, ImplicitSystemDeleter> implicit;

  State(const SinterScene& scene, Material material);
};

// Each column's top plane and thickness from s.top (flat at z_top when empty).
void set_top_planes(Sinter::State& s);
// Raises column `column`'s solid by `rise` m (a particle merged into the pool, wetting.cpp):
// its top node thickens, and past one dz the node above joins the solid at the top node's
// enthalpy density (the energy is unchanged: the same e over the same total volume).
void raise_column(Sinter::State& s, std::size_t column, double rise);
// Copies row 0 of every substrate field onto its image across a periodic seam (row ny - 1;
// periodic_seam.cpp); nothing without periodic_y.
void copy_image_row(Sinter::State& s);
// Laser models (laser_sources.cpp): chooses s.particle_laser and s.substrate_laser for the
// scene and, for ray tracing, builds the tracer.
void setup_laser(Sinter::State& s, const bed::Bed& bed);
// The tracer's optics from the scene's absorptivities or refractive indices.
SurfaceOptics surface_optics(const SinterScene& scene);
// Ray tracing: traces the beam positions [t0, t1] needs (with the phases of now) and sets the
// particle substeps so the laser raises no particle by more than time.max-particle-rise.
void prepare_traces(Sinter::State& s, double t0, double t1);
// Fraction of the beam the bed of the start state absorbs with the beam centred at (x, y)
// (ray tracing: of what reaches the substrate's extent).
double absorbed_fraction(const Sinter::State& s, double x, double y);
// Nodes at or above this are in the depression's cavity: T_d less half the phase-change window
// (drill() fills a node to T_d exactly; conduction then cools it by a fraction of a kelvin, which
// must not close the cavity step by step).
inline double cavity_temperature(const Sinter::State& s) {
  return s.depression_temperature - 0.5 * s.scene.phase_change.window;
}
// The surface node of column `column`: its top node, or with the depression the column's
// topmost node below the cavity (vapour_depression.hpp; the lowest free node at most).
std::size_t surface_node(const Sinter::State& s, std::size_t column);
// Laser energy onto the top face of column `column` over this grid step: into its top node, or
// with the depression booked on the column for drill().
void add_surface_energy(Sinter::State& s, std::size_t column, double energy);
// The depression: adds each column's laser energy of the step to its nodes' enthalpies from
// the surface down, none beyond T_d (NumericalError when the lowest free node is full: the
// depression has reached the grid's bottom). Called by the grid step after its sources.
void drill(Sinter::State& s);
// Conductivity at temperature t: the table's with variable-properties (Variable), else held at
// T0. A template argument, so a loop over contacts chooses once, not per contact.
template <bool Variable>
double conductivity_at(const Sinter::State& s, double t) {
  if constexpr (Variable) return s.conductivity(t);
  else return s.k_fixed;
}

// Wetting (wetting.cpp): set-up of the adjacency; after the particle steps of a grid step,
// spreads the contacts of particles that have just melted; the exact exchange of the spread
// substrate contacts over dt (energy handed to the grid as sources).
void setup_wetting(Sinter::State& s);
void spread_molten(Sinter::State& s);
void wetted_exchange(Sinter::State& s, double dt);
// The particle's stable step with its present contacts; more substeps if it is now shorter.
void recheck_particle_step(Sinter::State& s, std::size_t i);
// Whether particle i is wholly molten (past its melting window).
inline bool wholly_molten(const Sinter::State& s, std::size_t i) {
  return s.temperature[i] >= s.scene.phase_change.melting_point + 0.5 * s.scene.phase_change.window;
}
// Coalescence (coalescence.cpp): wholly molten particles in contact become one drop; the
// particles touching one that merged into the pool touch the pool.
void coalesce_molten(Sinter::State& s);
void touch_pool(Sinter::State& s, std::size_t merged);
// Whether particle i has merged into the pool or into another drop (gone, but not as vapour).
inline bool merged_away(const Sinter::State& s, std::size_t i) {
  return !s.merged.empty() && (s.merged[i] || s.coalesced_into[i] != i);
}
// The depression on particle i (evaporation.cpp), hotter than its T_d(r): the excess evaporated.
void ablate(Sinter::State& s, std::size_t i);
// A particle whose evaporated mass leaves less than this fraction of its start has left the bed.
inline constexpr double kVaporisedMass = 1e-3;
// New enthalpy or mass of particle i: temperature, peak and vaporisation follow (without
// evaporation: past the vaporisation window; with it: its mass evaporated).
inline void particle_state_changed(Sinter::State& s, std::size_t i) {
  const double temp = s.per_kg.temperature(s.h[i]);
  s.temperature[i] = temp;
  if (temp > s.peak[i]) s.peak[i] = temp;
  if (temp >= s.vaporised_temperature || s.mass[i] < kVaporisedMass * s.initial_mass[i]) {
    s.gone[i] = 1;  // left the bed as vapour
    ++s.gone_count;
  }
}
// New enthalpy of particle i; with the depression none is hotter than its T_d(r) (ablate).
inline void particle_enthalpy_changed(Sinter::State& s, std::size_t i) {
  if (s.per_kg.temperature(s.h[i]) > s.particle_depression_temperature[i]) ablate(s, i);
  else particle_state_changed(s, i);
}

// Per-track statistics (track_stats.cpp): the probes of each segment and the first window;
// after each step, the window's peaks (and a new window when the next segment has begun); at
// the end, the last window closed into s.tracks.
void setup_tracks(Sinter::State& s);
void watch_tracks(Sinter::State& s);
void close_tracks(Sinter::State& s);
// Internal energy of the particles and of the free substrate nodes, J, from T0.
std::pair<double, double> internal_energy(const Sinter::State& s);
// The highest temperatures so far, of the particles and of the substrate (summarise.cpp).
PeakTemperatures peak_temperatures(const Sinter::State& s);
// The run's result from its end state, its energies measured against those at its start
// (summarise.cpp); throws NumericalError if the energy balance is broken.
SinterResult summarise(Sinter::State& s, double particles_start, double substrate_start);

// Evaporation (evaporation.cpp) over dt: from the exposed particles (mass, energy), and from
// the substrate's surface nodes (from their enthalpies, before the grid step).
void evaporate_particles(Sinter::State& s, double dt);
void evaporate_surface(Sinter::State& s, double dt);
// One grid step of forward Euler (explicit_step.cpp): particles subcycle, then the grid.
void explicit_step(Sinter::State& s, double dt);
// One backward-Euler step of particles and free nodes together (implicit_step.cpp).
void implicit_step(Sinter::State& s, double dt);
// The top node of column `column` (i + nx j).
inline std::size_t top_node(const Sinter::State& s, std::size_t column) {
  return s.g.node(column, s.top_plane[column]);
}
// The thickness over dz of column `column`'s node in plane k: 1 below its top node, the top
// node's own, 0 above (empty).
inline double column_thickness(const Sinter::State& s, std::size_t column, std::size_t k) {
  const std::size_t top = s.top_plane[column];
  return k < top ? 1.0 : k == top ? s.top_thickness[column] : 0.0;
}
// A node's thickness over dz.
inline double node_thickness(const Sinter::State& s, std::size_t node) {
  const std::size_t plane = s.g.columns();
  return column_thickness(s, node % plane, node / plane);
}
// Volume of a node (0: empty).
inline double node_volume(const Sinter::State& s, std::size_t node) {
  return s.g.cell_volume() * node_thickness(s, node);
}

// The beam at time t (off between segments and after the path).
inline ScanSchedule::Beam beam_at(const Sinter::State& s, double t) { return s.schedule.at(t); }
// The laser's parameters with segment power p.
inline LaserParams laser_with_power(const Sinter::State& s, double p) {
  LaserParams l = s.laser;
  l.power = p;
  return l;
}
// Throws NumericalError if any temperature is non-finite, naming the particle or node; the
// substrate nodes only when `grid` is set (the particles are few, the grid is not).
void check_finite(const Sinter::State& s, bool grid = true);

}  // namespace powderbed::thermal

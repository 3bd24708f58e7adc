#pragma once
// The DE–FD laser thermal solver (docs/physics.md §5): lumped particle enthalpies on a fixed bed
// coupled to the finite-difference substrate, under a Gaussian laser moving along x.
//
// Time integration (explicit): each grid step dt_grid holds `substeps` particle steps
// (multirate: the particles' stable step and the grid's differ by orders of magnitude, so the
// smaller one subcycles); particles see the substrate temperatures of the start of the grid
// step and the energy they exchange with it is handed to the grid as a source, so the coupling
// conserves energy exactly. Implicit (backward Euler) solves particles and free nodes together.
// State variables are enthalpies (enthalpy.hpp); every joule is booked in an EnergyLedger.
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "powderbed/bed/bed.hpp"
#include "powderbed/thermal/bed_surface.hpp"
#include "powderbed/thermal/enthalpy.hpp"
#include "powderbed/thermal/material.hpp"
#include "powderbed/thermal/network.hpp"
#include "powderbed/thermal/scene.hpp"
#include "powderbed/thermal/substrate.hpp"

namespace powderbed::thermal {

// Energy booked over a run, J. Gains are positive into the bed + substrate.
struct EnergyLedger {
  double laser_particles = 0, laser_substrate = 0;
  double convection = 0, radiation = 0;  // into the particles (negative: losses)
  // Into particles and substrate (negative: a loss): latent heat of what evaporated, and the
  // enthalpy above T0 the evaporated particle mass carried off.
  double evaporation = 0;
  double boundary = 0;                   // into the Dirichlet sides and bottom (outflow)
  double internal_particles = 0, internal_substrate = 0;  // change, from the state enthalpies
  double absorbed() const { return laser_particles + laser_substrate; }
  // |absorbed + surface gains - internal change - boundary outflow| / absorbed.
  double relative_error() const;
};

struct MeltPool {  // on the plane x = Lx/2 (melt_pool.hpp says how)
  double height = 0, width = 0, depth = 0;  // m
};

// The melt pool on every cross-section of the track's steady part, as a user measures a track
// in several polished sections: mean and standard deviation of width and depth (m) over the
// grid columns between a quarter and three quarters of the bed's length (the single track on
// the grid's line j = ny/2 only, where the peaks below the top face are kept; none otherwise).
struct MeltPoolAlong {
  std::size_t sections = 0;
  double width_mean = 0, width_sd = 0, depth_mean = 0, depth_sd = 0;
};

// One segment of the scan path, measured over its window: from its start to the next segment's
// (the jump after it included; the last one to t_end). Width and depth on the cross-section
// through the segment's midpoint (melt_pool.hpp, measure_section), from the peaks of the window
// (of what got hotter in it: what is still molten from the track before but cooling is not);
// length: the longest stretch of the segment's centre line molten at once (top face at or above
// T_m, or a molten particle over it); peak temperature over the particles and the top face.
// What the track leaves for the next: the stored energy above T0 (bed + substrate) at the end of
// its window, and the mean top-face temperature within one spot radius of its own start as it
// starts (what the tracks before it left there).
struct TrackStats {
  MeltPool pool;
  double length = 0;            // m
  double peak_temperature = 0;  // K
  std::size_t particles_molten = 0;  // particles that got hotter and reached T_m in the window
  double start_temperature = 0;      // K
  double stored_energy = 0;          // J above T0 at the window's end
  double t_start = 0, t_end = 0;     // the window, s
};

struct StableSteps {
  double grid = 0;      // forward-Euler bound of the substrate, s
  double particle = 0;  // forward-Euler bound of the particles (inf: none)
  std::size_t grid_node = 0;       // where the grid bound is set
  std::size_t particle_index = 0;  // where the particle bound is set
};

// Where the peak temperatures of a run were: over the particles and over the substrate's nodes
// (its surface: the hottest node is at the top face or the depression's wall).
struct PeakTemperatures {
  double particles = 0, substrate = 0;
  double highest() const { return particles > substrate ? particles : substrate; }
};

struct SinterProgress {
  double time, t_end;
  PeakTemperatures peaks;
  std::uint64_t step;
};

// Ray tracing over a run: how the traced beam positions split the power (fractions of the beam,
// summed over traces).
struct TraceSummary {
  std::size_t traces = 0;
  double absorbed = 0, absorbed_particles = 0, escaped = 0, outside = 0, dropped = 0, hits = 0;
  double absorbed_depression = 0;
  // Absorbed over what reached the bed (the beam less what fell beyond the substrate's extent).
  double bed_absorptance() const { return absorbed / (static_cast<double>(traces) - outside); }
};

struct SinterResult {
  MeltPool melt_pool;
  MeltPoolAlong along;
  double max_temperature = 0;  // peaks.highest()
  PeakTemperatures peaks;
  // Evaporation: mass evaporated (particles + substrate), kg, and the peak recoil pressure,
  // Pa; the depression: T_d (0 without it), its deepest point below the top face, m, and
  // the share of the absorbed beam power its walls took.
  double evaporated_mass = 0, evaporated_mass_particles = 0, peak_recoil_pressure = 0;
  double depression_temperature = 0, depression_depth = 0;
  std::size_t particles_molten = 0, particles_vaporised = 0;
  EnergyLedger energy;
  std::uint64_t steps = 0, particle_steps = 0;
  double dt_grid = 0, dt_particle = 0, t_end = 0;
  std::size_t implicit_iterations = 0;  // total linear-solver iterations (implicit only)
  double absorptance = 0;  // laser energy absorbed over the beam's energy P t_end
  TraceSummary traces;     // ray tracing only
  std::size_t substrate_wetted = 0, bridges = 0;  // wetting: spread caps and liquid bridges
  std::size_t substrate_arrested = 0;  // wetting: caps of particles still there and arrested at t_end
  std::size_t particles_merged = 0;  // wetting: wholly molten on remelted solid, into the pool
  std::size_t particles_coalesced = 0;  // wetting: wholly molten, into a molten neighbour
  std::vector<TrackStats> tracks;  // one per scan segment begun by t_end
};

class Sinter {
 public:
  // Checks the bed against the substrate (3D, resting on its floor, nothing below it) and the
  // scene; throws InputError naming what is wrong.
  Sinter(const bed::Bed& bed, const SinterScene& scene, const MaterialTable& table);
  // On a raised solid top (fusion.hpp: one height per top-face column, none below the floor;
  // explicit integrator only): the bed rests on it and its particles touch it at its height.
  Sinter(const bed::Bed& bed, const SinterScene& scene, const MaterialTable& table, TopHeight top);
  ~Sinter();
  Sinter(const Sinter&) = delete;
  Sinter& operator=(const Sinter&) = delete;

  const StableSteps& stable_steps() const;
  double dt() const;          // the grid step the run takes
  std::size_t substeps() const;  // particle steps per grid step
  double t_end() const;
  const SubstrateGeometry& grid() const;
  const TopHeight& top_height() const;  // empty: flat at the plate's top face
  const SinterScene& scene() const;
  // The path the beam runs: the scene's scan path, or its single track resolved (the [GZ]
  // defaults for what the scene left NaN).
  const std::vector<ScanSegment>& scan_path() const;
  const std::vector<double>& particle_mass() const;  // rho(T0) 4/3 π r^3 less what evaporated, kg
  // Per particle, whether it merged into the pool (wetting): its volume is in top_height()
  // already. Empty without wetting.
  const std::vector<std::uint8_t>& particle_merged() const;
  // Per particle, the drop it coalesced into (wetting: wholly molten into a molten neighbour,
  // which took its mass; itself while it has not). Empty without wetting.
  const std::vector<std::uint32_t>& particle_coalesced_into() const;
  // The particles' heights and radii now: the bed's, but a drop that coalesced has grown (its
  // bottom where it was).
  const std::vector<double>& particle_z() const;
  const std::vector<double>& particle_radius() const;
  const BedSurface& surface() const;
  const ConductionNetwork& network() const;
  const Material& material() const;
  double extinction() const;  // beta, 1/m
  // Fraction of the beam the bed absorbs with the beam centred at (x, track line), at the start
  // state: the laser model's expected absorptance (--explain).
  double absorptance_at(double x) const;

  // Runs to t_end. `snapshot` is called at t = 0, every `every` grid steps and at the end;
  // `progress` about once a second of wall time. Throws NumericalError naming the particle or
  // node and the step if a temperature goes non-finite.
  SinterResult run(const std::function<void(const Sinter&)>& snapshot, std::uint64_t every,
                   const std::function<void(const SinterProgress&)>& progress);

  // State, for snapshots and tests.
  double time() const;
  std::uint64_t step() const;
  const std::vector<double>& particle_temperature() const;
  const std::vector<double>& particle_max_temperature() const;
  std::vector<std::uint8_t> particle_phase() const;
  const std::vector<double>& substrate_temperature() const;
  // Peak temperature of every node (T0 for the empty nodes over a column's top): a node whose
  // peak reached T_m was molten in this run.
  const std::vector<double>& substrate_peak() const;
  // Per column (i + nx j), the plane of its top node (grid().k_plate() where the top is flat).
  const std::vector<std::uint32_t>& top_planes() const;
  // Sets one particle's or one node's temperature (tests: initial conditions other than T0; on
  // a Dirichlet node it sets the boundary value).
  void set_particle_temperature(std::size_t i, double t);
  void set_substrate_temperature(std::size_t node, double t);

 // Opaque: defined inside libthermal, where the step routines share it.
  struct State;

 private:
  std::unique_ptr<State> s_;
};

}  // namespace powderbed::thermal

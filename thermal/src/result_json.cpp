// The JSON of a run's result (result_json.hpp).
#include "powderbed/thermal/result_json.hpp"

#include <cstdint>
#include <vector>

namespace powderbed::thermal {
namespace {

// --json "tracks": per scan segment, its melt pool and what it leaves for the next (SI).
void tracks_json(bed::JsonWriter& j, const std::vector<TrackStats>& tracks) {
  j.begin_array("tracks");
  for (const auto& t : tracks) {
    j.begin_object()
        .value("width", t.pool.width)
        .value("depth", t.pool.depth)
        .value("height", t.pool.height)
        .value("length", t.length)
        .value("peak_temperature", t.peak_temperature)
        .value("particles_molten", static_cast<std::uint64_t>(t.particles_molten))
        .value("start_temperature", t.start_temperature)
        .value("stored_energy", t.stored_energy)
        .value("t_start", t.t_start)
        .value("t_end", t.t_end)
        .end_object();
  }
  j.end_array();
}

// --json "ray_trace": how the traced beam positions split the power, fractions of the beam.
void ray_trace_json(bed::JsonWriter& j, const TraceSummary& t) {
  const double n = static_cast<double>(t.traces);
  j.begin_object("ray_trace")
      .value("traces", static_cast<std::uint64_t>(t.traces))
      .value("bed_absorptance", t.bed_absorptance())
      .value("particles", t.absorbed_particles / n)
      .value("substrate", (t.absorbed - t.absorbed_particles) / n)
      .value("escaped", t.escaped / n)
      .value("outside", t.outside / n)
      .value("dropped", t.dropped / n)
      .value("hits_per_ray", t.hits / n)
      .value("depression", t.absorbed_depression / n)
      .end_object();
}

// --json "energy": the run's ledger, J.
void energy_json(bed::JsonWriter& j, const EnergyLedger& e) {
  j.begin_object("energy")
      .value("laser_particles", e.laser_particles)
      .value("laser_substrate", e.laser_substrate)
      .value("convection", e.convection)
      .value("radiation", e.radiation)
      .value("evaporation", e.evaporation)
      .value("boundary", e.boundary)
      .value("internal_particles", e.internal_particles)
      .value("internal_substrate", e.internal_substrate)
      .end_object();
}

}  // namespace

void write_melt_pool_json(bed::JsonWriter& j, const SinterResult& r) {
  j.begin_object("melt_pool")
      .value("height", r.melt_pool.height)
      .value("width", r.melt_pool.width)
      .value("depth", r.melt_pool.depth)
      .end_object()
      .begin_object("melt_pool_along")
      .value("sections", static_cast<std::uint64_t>(r.along.sections))
      .value("width_mean", r.along.width_mean)
      .value("width_sd", r.along.width_sd)
      .value("depth_mean", r.along.depth_mean)
      .value("depth_sd", r.along.depth_sd)
      .end_object()
      .value("max_temperature", r.max_temperature)
      .value("max_temperature_particles", r.peaks.particles)
      .value("max_temperature_substrate", r.peaks.substrate)
      .value("evaporated_mass", r.evaporated_mass)
      .value("evaporated_mass_particles", r.evaporated_mass_particles)
      .value("peak_recoil_pressure", r.peak_recoil_pressure)
      .value("depression_temperature", r.depression_temperature)
      .value("depression_depth", r.depression_depth);
}

void write_run_json(bed::JsonWriter& j, const SinterResult& r) {
  j.value("particles_molten", static_cast<std::uint64_t>(r.particles_molten))
      .value("particles_vaporised", static_cast<std::uint64_t>(r.particles_vaporised))
      .value("energy_balance_error", r.energy.relative_error())
      .value("absorptance", r.absorptance);
  tracks_json(j, r.tracks);
  if (r.traces.traces > 0) ray_trace_json(j, r.traces);
  j.value("substrate_wetted", static_cast<std::uint64_t>(r.substrate_wetted))
      .value("substrate_arrested", static_cast<std::uint64_t>(r.substrate_arrested))
      .value("particles_merged", static_cast<std::uint64_t>(r.particles_merged))
      .value("particles_coalesced", static_cast<std::uint64_t>(r.particles_coalesced))
      .value("bridges", static_cast<std::uint64_t>(r.bridges));
  energy_json(j, r.energy);
  j.value("steps", r.steps)
      .value("particle_steps", r.particle_steps)
      .value("dt", r.dt_grid)
      .value("dt_particle", r.dt_particle)
      .value("t_end", r.t_end)
      .value("implicit_iterations", static_cast<std::uint64_t>(r.implicit_iterations));
}

}  // namespace powderbed::thermal

#include "sinter_summary.hpp"

#include <pybind11/stl.h>

#include <vector>

namespace py = pybind11;

namespace powderbed::python {

namespace th = thermal;

namespace {

py::dict energy_dict(const th::EnergyLedger& e) {
  py::dict d;
  d["laser_particles"] = e.laser_particles;
  d["laser_substrate"] = e.laser_substrate;
  d["convection"] = e.convection;
  d["radiation"] = e.radiation;
  d["evaporation"] = e.evaporation;
  d["boundary"] = e.boundary;
  d["internal_particles"] = e.internal_particles;
  d["internal_substrate"] = e.internal_substrate;
  return d;
}

py::list tracks_list(const std::vector<th::TrackStats>& tracks) {
  py::list out;
  for (const th::TrackStats& t : tracks) {
    py::dict d;
    d["width"] = t.pool.width;
    d["depth"] = t.pool.depth;
    d["height"] = t.pool.height;
    d["length"] = t.length;
    d["peak_temperature"] = t.peak_temperature;
    d["particles_molten"] = t.particles_molten;
    d["start_temperature"] = t.start_temperature;
    d["stored_energy"] = t.stored_energy;
    d["t_start"] = t.t_start;
    d["t_end"] = t.t_end;
    out.append(d);
  }
  return out;
}

}  // namespace

py::dict sinter_result_dict(const th::SinterResult& r) {
  py::dict d, pool, along;
  pool["height"] = r.melt_pool.height;
  pool["width"] = r.melt_pool.width;
  pool["depth"] = r.melt_pool.depth;
  along["sections"] = r.along.sections;
  along["width_mean"] = r.along.width_mean;
  along["width_sd"] = r.along.width_sd;
  along["depth_mean"] = r.along.depth_mean;
  along["depth_sd"] = r.along.depth_sd;
  d["melt_pool"] = pool;
  d["melt_pool_along"] = along;
  d["max_temperature"] = r.max_temperature;
  d["max_temperature_particles"] = r.peaks.particles;
  d["max_temperature_substrate"] = r.peaks.substrate;
  d["evaporated_mass"] = r.evaporated_mass;
  d["evaporated_mass_particles"] = r.evaporated_mass_particles;
  d["peak_recoil_pressure"] = r.peak_recoil_pressure;
  d["depression_temperature"] = r.depression_temperature;
  d["depression_depth"] = r.depression_depth;
  d["particles_molten"] = r.particles_molten;
  d["particles_vaporised"] = r.particles_vaporised;
  d["energy_balance_error"] = r.energy.relative_error();
  d["energy"] = energy_dict(r.energy);
  d["absorptance"] = r.absorptance;
  d["tracks"] = tracks_list(r.tracks);
  d["substrate_wetted"] = r.substrate_wetted;
  d["particles_merged"] = r.particles_merged;
  d["bridges"] = r.bridges;
  d["steps"] = r.steps;
  d["particle_steps"] = r.particle_steps;
  d["dt"] = r.dt_grid;
  d["dt_particle"] = r.dt_particle;
  d["t_end"] = r.t_end;
  d["implicit_iterations"] = r.implicit_iterations;
  return d;
}

}  // namespace powderbed::python

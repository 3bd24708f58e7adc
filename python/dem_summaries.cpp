#include "dem_summaries.hpp"

#include <pybind11/stl.h>

#include <cstdint>

namespace py = pybind11;

namespace powderbed::python {

namespace {

py::dict lid_dict(const dem::LidSummary& l) {
  py::dict d;
  d["start_z"] = l.start_z;
  d["surface_z"] = l.surface_z;
  d["stop_z"] = l.stop_z;
  d["travel"] = l.start_z - l.stop_z;
  d["target_force"] = l.target_force;
  d["stop_force"] = l.stop_force;
  d["max_force"] = l.max_force;
  d["hold_end_force"] = l.hold_end_force;
  d["hold_end_z"] = l.hold_end_z;
  d["hold_late_force"] = l.hold_late_force;
  d["stopped_by"] = l.stopped_by;
  d["release_time"] = l.release_time;
  return d;
}

}  // namespace

py::dict layer_summary_dict(const dem::LayerSummary& l) {
  py::dict d;
  d["layer"] = l.layer;
  d["n"] = l.n;
  d["supplied"] = l.supplied;
  d["steps"] = l.steps;
  d["sim_time"] = l.sim_time;
  d["wall_time"] = l.wall_time;
  d["tool_bottom"] = l.tool_bottom;
  d["max_tool_force"] = l.max_tool_force;
  d["mean_tool_force_x"] = l.mean_tool_force_x;
  d["kinetic_energy"] = l.kinetic_energy;
  d["max_speed"] = l.max_speed;
  d["density_under_gap"] = l.density_under_gap;
  d["lost"] = l.lost;
  d["overflow"] = l.overflow;
  d["frozen"] = l.frozen;
  d["frozen_tool_contacts"] = l.frozen_tool_contacts;
  return d;
}

py::dict run_summary_dict(const dem::RunSummary& r) {
  py::dict d;
  d["n"] = r.n;
  d["steps"] = r.steps;
  d["sim_time"] = r.sim_time;
  d["wall_time"] = r.wall_time;
  d["particle_steps_per_s"] = r.particle_steps_per_s;
  d["dt"] = r.dt;
  d["dt_stable"] = r.dt_stable;
  d["dt_limited_by"] = r.dt_limited_by;
  d["dt_limiting_radius"] = r.dt_limiting_radius;
  d["kinetic_energy"] = r.kinetic_energy;
  d["max_speed"] = r.max_speed;
  d["max_overlap"] = r.max_overlap;
  d["max_overlap_m"] = r.max_overlap_m;
  d["max_overlap_full_stiffness"] = r.max_overlap_full_stiffness;
  d["lost"] = r.lost;
  d["at_rest"] = r.at_rest;
  d["neighbour_rebuilds"] = r.neighbour_rebuilds;
  if (r.inserted > 0 || !r.insertion_stopped_by.empty()) {
    py::dict insertion;
    insertion["inserted"] = r.inserted;
    insertion["end_time"] = r.insertion_end;
    insertion["stopped_by"] = r.insertion_stopped_by;
    d["insertion"] = insertion;
  }
  if (r.lid_used) d["lid"] = lid_dict(r.lid);
  return d;
}

py::dict spread_summary_dict(const dem::SpreadSummary& s) {
  py::dict d;
  py::list layers;
  for (const dem::LayerSummary& l : s.layers) layers.append(layer_summary_dict(l));
  d["layers"] = layers;
  d["steps"] = s.steps;
  d["sim_time"] = s.sim_time;
  d["dt"] = s.dt;
  d["dt_stable"] = s.dt_stable;
  d["dt_limited_by"] = s.dt_limited_by;
  d["dt_limiting_radius"] = s.dt_limiting_radius;
  d["wall_time"] = s.wall_time;
  d["particle_steps_per_s"] = s.particle_steps_per_s;
  d["max_overlap"] = s.max_overlap;
  d["neighbour_rebuilds"] = s.neighbour_rebuilds;
  d["layers_done"] = s.state.layers_done;
  return d;
}

}  // namespace powderbed::python

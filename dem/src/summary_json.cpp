// summary_json.hpp: deposit's --json fields of a drop and a spread, and the Python dicts'.
#include "powderbed/dem/summary_json.hpp"

#include <cstdint>

namespace powderbed::dem {
namespace {

// The step's choice and its wall-clock rate: what a drop and a spread both report.
template <class Summary>
void write_steps(bed::JsonWriter& j, const Summary& r) {
  j.value("steps", r.steps)
      .value("sim_time", r.sim_time)
      .value("wall_time", r.wall_time)
      .value("particle_steps_per_s", r.particle_steps_per_s)
      .value("dt", r.dt)
      .value("dt_stable", r.dt_stable)
      .value("dt_limited_by", r.dt_limited_by)
      .value("dt_limiting_radius", r.dt_limiting_radius);
}

void write_lid_json(bed::JsonWriter& j, const LidSummary& l) {
  j.begin_object("lid")
      .value("start_z", l.start_z)
      .value("stop_z", l.stop_z)
      .value("surface_z", l.surface_z)
      .value("travel", l.start_z - l.stop_z)
      .value("target_force", l.target_force)
      .value("stop_force", l.stop_force)
      .value("max_force", l.max_force)
      .value("hold_end_force", l.hold_end_force)
      .value("hold_end_z", l.hold_end_z)
      .value("hold_late_force", l.hold_late_force)
      .value("stopped_by", l.stopped_by)
      .value("released", l.released)
      .value("release_time", l.release_time)
      .end_object();
}

}  // namespace

void write_run_json(bed::JsonWriter& j, const RunSummary& r) {
  write_steps(j, r);
  j.value("kinetic_energy", r.kinetic_energy)
      .value("max_speed", r.max_speed)
      .value("max_overlap", r.max_overlap)
      .value("max_overlap_m", r.max_overlap_m)
      .value("max_overlap_full_stiffness", r.max_overlap_full_stiffness)
      .value("at_rest", r.at_rest)
      .value("neighbour_rebuilds", r.neighbour_rebuilds);
  if (!r.insertion_stopped_by.empty()) {  // set whenever insertion ran (solver.cpp)
    j.begin_object("insertion")
        .value("inserted", static_cast<std::uint64_t>(r.inserted))
        .value("end_time", r.insertion_end)
        .value("stopped_by", r.insertion_stopped_by)
        .end_object();
  }
  if (r.lid_used) write_lid_json(j, r.lid);
}

void write_spread_json(bed::JsonWriter& j, const SpreadSummary& s) {
  write_steps(j, s);
  j.value("max_overlap", s.max_overlap)
      .value("neighbour_rebuilds", s.neighbour_rebuilds)
      .value("layers_done", s.state.layers_done);
  j.begin_array("layers");
  for (const LayerSummary& l : s.layers) {
    j.begin_object();
    write_layer_json(j, l);
    j.end_object();
  }
  j.end_array();
}

void write_layer_json(bed::JsonWriter& j, const LayerSummary& l) {
  j.value("layer", l.layer)
      .value("n", static_cast<std::uint64_t>(l.n))
      .value("supplied", static_cast<std::uint64_t>(l.supplied))
      .value("steps", l.steps)
      .value("sim_time", l.sim_time)
      .value("wall_time", l.wall_time)
      .value("tool_bottom", l.tool_bottom)
      .value("max_tool_force", l.max_tool_force)
      .value("mean_tool_force_x", l.mean_tool_force_x)
      .value("density_under_gap", l.density_under_gap)
      .value("kinetic_energy", l.kinetic_energy)
      .value("max_speed", l.max_speed)
      .value("lost", static_cast<std::uint64_t>(l.lost))
      .value("overflow", static_cast<std::uint64_t>(l.overflow))
      .value("under_platform", static_cast<std::uint64_t>(l.under_platform))
      .value("frozen", static_cast<std::uint64_t>(l.frozen))
      .value("frozen_tool_contacts", l.frozen_tool_contacts)
      .value("asleep", l.asleep)
      .value("sleep_changes", l.sleep_changes)
      .value("settle_time", l.settle_time)
      .value("at_rest", l.at_rest);
}

}  // namespace powderbed::dem

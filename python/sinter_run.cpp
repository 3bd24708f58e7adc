// sinter in-process: thermal::Sinter on a bed dict and a SinterScene, with the GIL released; the
// bed comes back with each particle's final temperature and phase, the result as a dict with the
// keys of sinter's --json summary (apps/sinter.cpp) where it has the same number.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <memory>
#include <tuple>

#include "bed_dict.hpp"
#include "bindings.hpp"
#include "gil_callback.hpp"
#include "python_warning.hpp"
#include "powderbed/bed/material_file.hpp"
#include "powderbed/thermal/material.hpp"
#include "powderbed/thermal/solver.hpp"

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

py::dict result_dict(const th::SinterResult& r, const th::Sinter& sinter) {
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
  d["dt_stable_grid"] = sinter.stable_steps().grid;
  d["dt_stable_particle"] = sinter.stable_steps().particle;
  d["t_end"] = r.t_end;
  d["implicit_iterations"] = r.implicit_iterations;
  return d;
}

// sinter's warning (apps/sinter.cpp): unsafe_dt lets an explicit step above the bound through.
void warn_unsafe_dt(const th::SinterScene& scene, const th::Sinter& sinter) {
  if (scene.unsafe_dt && scene.dt > sinter.stable_steps().grid &&
      scene.integrator == th::Integrator::explicit_euler)
    warn(fmt::format("sinter: dt {:g} s is above the stable bound {:g} s (unsafe_dt)", scene.dt,
                     sinter.stable_steps().grid));
}

py::tuple sinter(const py::dict& bed_fields, const th::SinterScene& scene, const py::object& progress) {
  bed::Bed bed = bed_from_dict(bed_fields);
  std::function<void(const th::SinterProgress&)> report;
  if (given(progress)) {
    report = [fn = py::handle(progress)](const th::SinterProgress& p) {
      call_with_gil(fn, [&p] {
        py::dict d;
        d["step"] = p.step;
        d["time"] = p.time;
        d["t_end"] = p.t_end;
        d["fraction"] = p.time / p.t_end;
        d["max_temperature_particles"] = p.peaks.particles;
        d["max_temperature_substrate"] = p.peaks.substrate;
        return std::make_tuple(d);
      });
    };
  }
  std::unique_ptr<th::Sinter> run;
  {
    py::gil_scoped_release release;
    // A name of data/materials (316L) or a path, as the program resolves it.
    const th::MaterialTable table =
        th::read_material_table(bed::material_path(scene.material_table, "material_table"));
    run = std::make_unique<th::Sinter>(bed, scene, table);
  }
  warn_unsafe_dt(scene, *run);
  th::SinterResult result;
  {
    py::gil_scoped_release release;
    result = run->run({}, 0, report);
  }
  bed.temperature = run->particle_temperature();
  bed.phase = run->particle_phase();
  bed.provenance.stage = "sinter";
  return py::make_tuple(bed_to_dict(bed), result_dict(result, *run));
}

}  // namespace

void bind_sinter(py::module_& m) {
  m.def("sinter", &sinter, py::arg("bed"), py::arg("scene"), py::arg("progress"));
}

}  // namespace powderbed::python

// sinter in-process: thermal::Sinter on a bed dict and a SinterScene, with the GIL released; the
// bed comes back with each particle's final temperature and phase, the result as a dict with the
// keys of sinter's --json summary (apps/sinter.cpp) where it has the same number (a build's
// layers report their scans with it too).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <memory>
#include <tuple>

#include "bed_dict.hpp"
#include "bindings.hpp"
#include "gil_callback.hpp"
#include "python_warning.hpp"
#include "sinter_summary.hpp"
#include "powderbed/bed/material_file.hpp"
#include "powderbed/thermal/material.hpp"
#include "powderbed/thermal/solver.hpp"

namespace py = pybind11;

namespace powderbed::python {

namespace th = thermal;

namespace {

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
  py::dict summary = sinter_result_dict(result);
  summary["dt_stable_grid"] = run->stable_steps().grid;
  summary["dt_stable_particle"] = run->stable_steps().particle;
  return py::make_tuple(bed_to_dict(bed), summary);
}

}  // namespace

void bind_sinter(py::module_& m) {
  m.def("sinter", &sinter, py::arg("bed"), py::arg("scene"), py::arg("progress"));
}

}  // namespace powderbed::python

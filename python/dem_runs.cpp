// deposit and spread in-process: the bed dict in, dem::run_deposition / dem::run_spread on the
// bound structs with the GIL released, the bed dict and the summary out. The pure-Python half
// (powderbed/_runs.py) spreads keyword arguments over the structs and checks the callables.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <optional>
#include <string>
#include <tuple>

#include "bed_dict.hpp"
#include "bindings.hpp"
#include "powderbed/dem/contact_provenance.hpp"
#include "dem_summaries.hpp"
#include "gil_callback.hpp"
#include "python_warning.hpp"
#include "supply_maker.hpp"
#include "powderbed/dem/solver.hpp"
#include "powderbed/dem/spread.hpp"
#include "powderbed/dem/time_step.hpp"

namespace py = pybind11;

namespace powderbed::python {

namespace {

// deposit's warning (apps/deposit.cpp warn_unsafe_dt): unsafe_dt lets a step above the stable
// bound through, and the user is told so.
void warn_unsafe_dt(const bed::Bed& bed, const dem::Scene& scene, double dt, bool unsafe,
                    double young_scale, const char* what) {
  if (!unsafe || !(dt > 0)) return;
  scene.validate();
  const double stable = dem::time_step_bound(bed, scene, young_scale).stable;
  if (dt > stable)
    warn(fmt::format("{}: dt {:g} s is above the stable bound {:g} s (unsafe_dt)", what, dt, stable));
}

py::tuple deposit(const py::dict& bed_fields, const dem::Scene& scene, dem::RunSettings settings,
                  const py::object& progress) {
  bed::Bed bed = bed_from_dict(bed_fields);
  if (given(progress)) {
    settings.progress = [fn = py::handle(progress)](const dem::Progress& p) {
      call_with_gil(fn, [&p] {
        py::dict d;
        d["step"] = p.step;
        d["time"] = p.time;
        d["t_end"] = p.t_end;
        d["fraction"] = p.t_end > 0 ? p.time / p.t_end : 1.0;
        d["kinetic_energy"] = p.kinetic_energy;
        d["max_speed"] = p.max_speed;
        return std::make_tuple(d);
      });
    };
  }
  warn_unsafe_dt(bed, scene, settings.dt, settings.unsafe_dt, settings.young_scale, "deposit");
  dem::RunSummary summary;
  {
    py::gil_scoped_release release;
    summary = dem::run_deposition(bed, scene, settings);
  }
  bed.provenance.stage = "deposit";
  bed.provenance.contact = dem::contact_provenance(scene, settings.young_scale);
  return py::make_tuple(bed_to_dict(bed), run_summary_dict(summary));
}

py::tuple spread(const py::dict& bed_fields, const dem::Scene& scene, dem::SpreadSettings settings,
                 const py::object& state, const py::object& supply, const py::object& progress) {
  bed::Bed bed = bed_from_dict(bed_fields);
  if (given(supply)) settings.supply = supply_maker(supply);
  if (given(progress)) {
    settings.progress = [fn = py::handle(progress)](double fraction, double kinetic_energy) {
      call_with_gil(fn, [=] {
        py::dict d;
        d["fraction"] = fraction;
        d["kinetic_energy"] = kinetic_energy;
        return std::make_tuple(d);
      });
    };
  }
  const std::optional<dem::SpreadState> restart =
      state.is_none() ? std::nullopt : std::optional(state.cast<dem::SpreadState>());
  warn_unsafe_dt(bed, scene, settings.dt, settings.unsafe_dt, settings.young_scale, "spread");
  dem::SpreadSummary summary;
  {
    py::gil_scoped_release release;
    summary = dem::run_spread(bed, scene, settings, restart ? &*restart : nullptr);
  }
  bed.provenance.stage = "spread";
  bed.provenance.contact = dem::contact_provenance(scene, settings.young_scale);
  return py::make_tuple(bed_to_dict(bed), spread_summary_dict(summary), py::cast(std::move(summary.state)));
}

}  // namespace

void bind_dem_runs(py::module_& m) {
  m.def("deposit", &deposit, py::arg("bed"), py::arg("scene"), py::arg("settings"),
        py::arg("progress"));
  m.def("spread", &spread, py::arg("bed"), py::arg("scene"), py::arg("settings"), py::arg("state"),
        py::arg("supply"), py::arg("progress"));
}

}  // namespace powderbed::python

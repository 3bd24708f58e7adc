#include "dem_summaries.hpp"

#include <cstdint>

#include "json_dict.hpp"
#include "powderbed/dem/summary_json.hpp"

namespace py = pybind11;

namespace powderbed::python {

py::dict layer_summary_dict(const dem::LayerSummary& l) {
  return json_dict([&](bed::JsonWriter& j) { dem::write_layer_json(j, l); });
}

py::dict run_summary_dict(const dem::RunSummary& r) {
  return json_dict([&](bed::JsonWriter& j) {
    j.value("n", static_cast<std::uint64_t>(r.n)).value("lost", static_cast<std::uint64_t>(r.lost));
    dem::write_run_json(j, r);
  });
}

py::dict spread_summary_dict(const dem::SpreadSummary& s) {
  return json_dict([&](bed::JsonWriter& j) { dem::write_spread_json(j, s); });
}

}  // namespace powderbed::python

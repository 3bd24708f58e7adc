#include "dem_summaries.hpp"

#include <cstdint>

#include "powderbed/bed/json.hpp"
#include "powderbed/dem/summary_json.hpp"

namespace py = pybind11;

namespace powderbed::python {

namespace {

// The writer's object as a dict: json.loads of the text deposit's --json is made of.
template <class Write>
py::dict loads(Write&& write) {
  bed::JsonWriter j;
  j.begin_object();
  write(j);
  j.end_object();
  return py::module_::import("json").attr("loads")(j.str());
}

}  // namespace

py::dict layer_summary_dict(const dem::LayerSummary& l) {
  return loads([&](bed::JsonWriter& j) { dem::write_layer_json(j, l); });
}

py::dict run_summary_dict(const dem::RunSummary& r) {
  return loads([&](bed::JsonWriter& j) {
    j.value("n", static_cast<std::uint64_t>(r.n)).value("lost", static_cast<std::uint64_t>(r.lost));
    dem::write_run_json(j, r);
  });
}

py::dict spread_summary_dict(const dem::SpreadSummary& s) {
  return loads([&](bed::JsonWriter& j) { dem::write_spread_json(j, s); });
}

}  // namespace powderbed::python

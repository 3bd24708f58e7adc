#include "build_report.hpp"

#include "dem_summaries.hpp"
#include "powderbed/bed/json.hpp"
#include "powderbed/process/build_report.hpp"
#include "sinter_summary.hpp"

namespace py = pybind11;

namespace powderbed::python {

py::dict layer_report_dict(const process::LayerReport& l) {
  // build.json's layer object, written by the program's writer; no pictures (none are drawn).
  bed::JsonWriter j;
  process::write_layer_json(j, l, {});
  py::dict d = py::module_::import("json").attr("loads")(j.str());
  d.attr("pop")("pictures");
  // The stages' own summaries, as spread and sinter return them.
  d["spread"] = layer_summary_dict(l.spread);
  d["scan"] = sinter_result_dict(l.scan);
  return d;
}

}  // namespace powderbed::python

#include "sinter_summary.hpp"

#include "powderbed/bed/json.hpp"
#include "powderbed/thermal/result_json.hpp"

namespace py = pybind11;

namespace powderbed::python {

py::dict sinter_result_dict(const thermal::SinterResult& r) {
  bed::JsonWriter j;
  j.begin_object();
  thermal::write_melt_pool_json(j, r);
  thermal::write_run_json(j, r);
  j.end_object();
  return py::module_::import("json").attr("loads")(j.str());
}

}  // namespace powderbed::python

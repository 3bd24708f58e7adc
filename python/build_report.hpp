#pragma once
// A build layer's report (process::LayerReport) as a Python dict: build.json's layer object
// (process/build_report.hpp writes it) less its pictures, with the spread's and the scan's own
// summaries under "spread" and "scan".
#include <pybind11/pybind11.h>

#include "powderbed/process/build_layer.hpp"

namespace powderbed::python {

pybind11::dict layer_report_dict(const process::LayerReport& l);

}  // namespace powderbed::python

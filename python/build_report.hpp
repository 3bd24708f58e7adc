#pragma once
// A build layer's report (process::LayerReport) as a Python dict, with the keys of build.json's
// layer objects where it has the same number (apps/build.cpp layer_json).
#include <pybind11/pybind11.h>

#include "powderbed/process/build_layer.hpp"

namespace powderbed::python {

pybind11::dict layer_report_dict(const process::LayerReport& l);

}  // namespace powderbed::python

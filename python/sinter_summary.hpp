#pragma once
// A scan's result as a Python dict (sinter_run.cpp): sinter's and each layer of a build's, the
// fields of sinter's --json (thermal's result_json.hpp), read back by json.loads.
#include <pybind11/pybind11.h>

#include "powderbed/thermal/solver.hpp"

namespace powderbed::python {

pybind11::dict sinter_result_dict(const thermal::SinterResult& r);

}  // namespace powderbed::python

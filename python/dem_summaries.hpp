#pragma once
// dem's run summaries as Python dicts: json.loads of dem's summary writer (summary_json.hpp),
// the fields deposit's --json summary holds, plus a drop's bed count and lost particles.
#include <pybind11/pybind11.h>

#include "powderbed/dem/solver.hpp"
#include "powderbed/dem/spread.hpp"

namespace powderbed::python {

pybind11::dict run_summary_dict(const dem::RunSummary& r);
pybind11::dict spread_summary_dict(const dem::SpreadSummary& s);
// One layer of a spread (a spread's and a build layer's).
pybind11::dict layer_summary_dict(const dem::LayerSummary& l);

}  // namespace powderbed::python

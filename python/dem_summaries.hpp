#pragma once
// dem's run summaries as Python dicts, with the keys of deposit's --json summary where it has
// the same number (apps/deposit.cpp, deposit_spread.cpp).
#include <pybind11/pybind11.h>

#include "powderbed/dem/solver.hpp"
#include "powderbed/dem/spread.hpp"

namespace powderbed::python {

pybind11::dict run_summary_dict(const dem::RunSummary& r);
pybind11::dict spread_summary_dict(const dem::SpreadSummary& s);
// One layer of a spread (a spread's and a build layer's).
pybind11::dict layer_summary_dict(const dem::LayerSummary& l);

}  // namespace powderbed::python

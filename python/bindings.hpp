#pragma once
// The parts of the module _core, one per library it binds (module.cpp calls them in order: the
// structs before the functions that take them).
#include <pybind11/pybind11.h>

namespace powderbed::python {

void bind_dem_structs(pybind11::module_& m);    // dem_structs.cpp
void bind_dem_runs(pybind11::module_& m);       // dem_runs.cpp: deposit, spread
void bind_keff(pybind11::module_& m);           // keff_binding.cpp
void bind_thermal_structs(pybind11::module_& m);  // thermal_structs.cpp
void bind_sinter(pybind11::module_& m);         // sinter_run.cpp
void bind_build(pybind11::module_& m);          // build_run.cpp
void bind_packgen(pybind11::module_& m);        // packgen_run.cpp: PackOptions, pack

}  // namespace powderbed::python

#pragma once
// A library's summary writer (dem's, packgen's summary_json.hpp) as a Python dict: json.loads of
// the very text the program's --json prints, so the dict and the program cannot drift apart.
#include <pybind11/pybind11.h>

#include "powderbed/bed/json.hpp"

namespace powderbed::python {

// The object `write(j)` fills, as a dict.
template <class Write>
pybind11::dict json_dict(Write&& write) {
  bed::JsonWriter j;
  j.begin_object();
  write(j);
  j.end_object();
  return pybind11::module_::import("json").attr("loads")(j.str());
}

}  // namespace powderbed::python

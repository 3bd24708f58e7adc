#pragma once
// A spread's supply from a Python callable (spread's and a build's): called holding the GIL
// (gil_callback.hpp) with the region as a domain dict and the layer, it returns the supply's bed
// dict (powderbed/_runs.py checks that the user's callable returned a Bed).
#include <pybind11/pybind11.h>

#include <cstdint>

#include "bed_dict.hpp"
#include "powderbed/dem/spread.hpp"

namespace powderbed::python {

inline dem::SupplyMaker supply_maker(pybind11::handle fn) {
  return [fn](const bed::Domain& region, std::uint64_t layer) {
    pybind11::gil_scoped_acquire gil;
    return bed_from_dict(fn(domain_to_dict(region), layer).cast<pybind11::dict>());
  };
}

}  // namespace powderbed::python

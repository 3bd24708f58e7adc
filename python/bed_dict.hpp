#pragma once
// A bed as the Python module hands it over: a dict of numpy arrays and plain values
// (python/powderbed/__init__.py wraps it in the Bed class), to and from bed::Bed.
#include <pybind11/pybind11.h>

#include "powderbed/bed/bed.hpp"

namespace powderbed::python {

// Keys: x, y, z, r, id (always); material, vx, vy, vz, temperature, phase (None when absent);
// domain {dimension, lower, upper, periodic}; provenance {created_by, command_line, rng_seed,
// stage, scene, contact_*}.
pybind11::dict bed_to_dict(const bed::Bed& bed);
// A domain as the dict a Bed holds: {dimension, lower, upper, periodic}.
pybind11::dict domain_to_dict(const bed::Domain& d);
// The inverse of domain_to_dict, validated; throws InputError on a bad domain.
bed::Domain domain_from_dict(const pybind11::dict& d);
// A box as a function's `domain` argument gives it: a dict as domain_to_dict's, or 2 or 3
// lengths (the box [0, L], as the programs' --domain); InputError naming `what` otherwise.
bed::Domain domain_from_python(const pybind11::object& domain, const char* what);
// The inverse of bed_to_dict; throws InputError naming the key when an array's length differs from x's.
bed::Bed bed_from_dict(const pybind11::dict& d);

}  // namespace powderbed::python

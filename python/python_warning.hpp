#pragma once
// What the programs print as "PROGRAM: warning: ..." on stderr, raised in Python as a
// RuntimeWarning through the warnings module (so filters, catch_warnings and -W error apply).
#include <pybind11/pybind11.h>

#include <string>

namespace powderbed::python {

// Needs the GIL. Under -W error (the warning became an exception) throws error_already_set.
inline void warn(const std::string& message) {
  if (PyErr_WarnEx(PyExc_RuntimeWarning, message.c_str(), 1) != 0) throw pybind11::error_already_set();
}

}  // namespace powderbed::python

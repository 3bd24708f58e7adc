#pragma once
// Python callables called from inside a run that released the GIL (progress, a spread's supply).
//
// The run holds a py::handle, not a py::object: the solvers copy their settings (and the
// std::function in them) while the GIL is released, and copying a py::object would touch its
// reference count without the GIL. The caller's own reference keeps the callable alive for the
// run. A Python exception in the callable leaves as py::error_already_set, which unwinds the
// solver as an InputError would (its state is RAII) and reaches Python as the callable's own
// exception once the GIL is back.
#include <pybind11/pybind11.h>

#include <tuple>
#include <utility>

namespace powderbed::python {

namespace py = pybind11;

// Calls `fn(args...)` holding the GIL; the arguments are built, and the result dropped, under
// it too (dicts, arrays: their reference counts need it).
template <class Make>
void call_with_gil(py::handle fn, Make&& make_args) {
  py::gil_scoped_acquire gil;
  std::apply([fn](auto&&... a) { fn(std::forward<decltype(a)>(a)...); }, make_args());
}

// Whether a progress argument is set: None means no callback.
inline bool given(const py::object& fn) { return !fn.is_none(); }

}  // namespace powderbed::python

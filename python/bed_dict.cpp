#include "bed_dict.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <string>
#include <vector>

#include "powderbed/bed/errors.hpp"

namespace py = pybind11;

namespace powderbed::python {

namespace {

template <class T>
py::object array_or_none(const std::vector<T>& v, bool present) {
  if (!present) return py::none();
  return py::array_t<T>(static_cast<py::ssize_t>(v.size()), v.data());
}

// The values of d[key] as T (any sequence numpy can convert); empty when absent or None.
template <class T>
std::vector<T> vector_of(const py::dict& d, const char* key, std::size_t n, bool required) {
  if (!d.contains(key) || d[key].is_none()) {
    if (required) throw InputError(std::string("bed: '") + key + "' is missing (required)");
    return {};
  }
  const auto a = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(d[key]);
  const bool any_length = n == static_cast<std::size_t>(-1);
  if (!a || a.ndim() != 1 || (!any_length && static_cast<std::size_t>(a.size()) != n)) {
    throw InputError(std::string("bed: '") + key + "' must be a 1-D array" +
                     (any_length ? "" : " of " + std::to_string(n) + " numbers (the length of x)"));
  }
  return std::vector<T>(a.data(), a.data() + a.size());
}

py::dict provenance_to_dict(const bed::Provenance& p) {
  py::dict out;
  out["created_by"] = p.created_by;
  out["command_line"] = p.command_line;
  out["rng_seed"] = p.rng_seed;
  out["stage"] = p.stage;
  out["scene"] = p.scene;
  if (p.contact.law.empty()) return out;
  out["contact_law"] = p.contact.law;
  out["contact_young"] = p.contact.young;
  out["contact_poisson"] = p.contact.poisson;
  out["contact_wall_young"] = p.contact.wall_young;
  out["contact_wall_poisson"] = p.contact.wall_poisson;
  out["contact_young_scale"] = p.contact.young_scale;
  out["contact_stiffness"] = p.contact.stiffness;
  return out;
}

template <class T>
void take(const py::dict& d, const char* key, T& value) {
  if (d.contains(key)) value = d[key].cast<T>();
}

bed::Provenance provenance_from_dict(const py::dict& d) {
  bed::Provenance p;
  take(d, "created_by", p.created_by);
  take(d, "command_line", p.command_line);
  take(d, "rng_seed", p.rng_seed);
  take(d, "stage", p.stage);
  take(d, "scene", p.scene);
  take(d, "contact_law", p.contact.law);
  take(d, "contact_young", p.contact.young);
  take(d, "contact_poisson", p.contact.poisson);
  take(d, "contact_wall_young", p.contact.wall_young);
  take(d, "contact_wall_poisson", p.contact.wall_poisson);
  take(d, "contact_young_scale", p.contact.young_scale);
  take(d, "contact_stiffness", p.contact.stiffness);
  return p;
}

// The domain of a dict as domain_to_dict gives it (pybind11 and Python errors as they come).
bed::Domain domain_fields(const py::dict& d) {
  bed::Domain out;
  out.dimension = d["dimension"].cast<int>();
  const auto lower = d["lower"].cast<std::vector<double>>();
  const auto upper = d["upper"].cast<std::vector<double>>();
  const auto periodic = d["periodic"].cast<std::vector<bool>>();
  if (lower.size() != 3 || upper.size() != 3 || periodic.size() != 3)
    throw InputError("bed: domain lower, upper and periodic need 3 values each");
  for (int a = 0; a < 3; ++a) {
    out.lower[a] = lower[a];
    out.upper[a] = upper[a];
    out.periodic[a] = periodic[a];
  }
  out.validate("bed: domain");
  return out;
}

}  // namespace

py::dict domain_to_dict(const bed::Domain& d) {
  py::dict out;
  out["dimension"] = d.dimension;
  out["lower"] = py::array_t<double>(3, d.lower.data());
  out["upper"] = py::array_t<double>(3, d.upper.data());
  out["periodic"] = std::vector<bool>(d.periodic.begin(), d.periodic.end());
  return out;
}

py::dict bed_to_dict(const bed::Bed& b) {
  py::dict d;
  d["x"] = array_or_none(b.x, true);
  d["y"] = array_or_none(b.y, true);
  d["z"] = array_or_none(b.z, true);
  d["r"] = array_or_none(b.radius, true);
  d["id"] = array_or_none(b.id, true);
  d["material"] = array_or_none(b.material, !b.material.empty());
  d["vx"] = array_or_none(b.vx, b.has_velocity());
  d["vy"] = array_or_none(b.vy, b.has_velocity());
  d["vz"] = array_or_none(b.vz, b.has_velocity());
  d["temperature"] = array_or_none(b.temperature, !b.temperature.empty());
  d["phase"] = array_or_none(b.phase, !b.phase.empty());
  d["domain"] = domain_to_dict(b.domain);
  d["provenance"] = provenance_to_dict(b.provenance);
  return d;
}

namespace {

bed::Bed bed_fields(const py::dict& d) {
  bed::Bed b;
  b.x = vector_of<double>(d, "x", static_cast<std::size_t>(-1), true);
  const std::size_t n = b.x.size();
  b.y = vector_of<double>(d, "y", n, true);
  b.z = vector_of<double>(d, "z", n, true);
  b.radius = vector_of<double>(d, "r", n, true);
  b.id = vector_of<std::uint64_t>(d, "id", n, true);
  b.material = vector_of<std::uint16_t>(d, "material", n, false);
  b.vx = vector_of<double>(d, "vx", n, false);
  b.vy = vector_of<double>(d, "vy", n, false);
  b.vz = vector_of<double>(d, "vz", n, false);
  b.temperature = vector_of<double>(d, "temperature", n, false);
  b.phase = vector_of<std::uint8_t>(d, "phase", n, false);
  b.domain = domain_fields(d["domain"].cast<py::dict>());
  if (d.contains("provenance")) b.provenance = provenance_from_dict(d["provenance"].cast<py::dict>());
  return b;
}

}  // namespace

namespace {

// read() of a Python value, with a missing key or a value of the wrong type (pybind11's
// cast_error, Python's KeyError) turned into what it is, bad input like any other: InputError,
// the documented ValueError, not a RuntimeError. `what` names the value, `accepted` what is.
template <class Read>
auto read_python(const char* what, const char* accepted, Read&& read) -> decltype(read()) {
  try {
    return read();
  } catch (const py::cast_error& e) {
    throw InputError(fmt::format("{} of the wrong type (accepted: {}): {}", what, accepted, e.what()));
  } catch (const py::error_already_set& e) {
    throw InputError(fmt::format("{} is missing or wrong (accepted: {}): {}", what, accepted, e.what()));
  }
}

constexpr const char* kAsDict = "the dict Bed.as_dict() gives";

}  // namespace

bed::Domain domain_from_dict(const py::dict& d) {
  return read_python("bed: a domain value", kAsDict, [&] { return domain_fields(d); });
}

bed::Domain domain_from_python(const py::object& domain, const char* what) {
  return read_python(what, "a dict as Bed.domain, or 2 or 3 lengths in m", [&] {
    return py::isinstance<py::dict>(domain) ? domain_fields(domain.cast<py::dict>())
                                            : bed::box_of_lengths(domain.cast<std::vector<double>>(), what);
  });
}

bed::Bed bed_from_dict(const py::dict& d) {
  return read_python("bed: a domain or provenance value", kAsDict, [&] { return bed_fields(d); });
}

}  // namespace powderbed::python

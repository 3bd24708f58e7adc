// The C++ half of the Python module `powderbed` (python/powderbed/__init__.py is the other):
// the bed library's readers and writers, PSD sampling and bedstat's statistics, so a script
// gets the same numbers as the programs without parsing their output; and the stages run
// in-process on the libraries' structs (bindings.hpp: packgen, deposit, spread, keff, sinter, build).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <set>
#include <string>
#include <utility>
#include <variant>

#include "bed_dict.hpp"
#include "bindings.hpp"
#include "powderbed/bed/bed_report.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/material_fills.hpp"
#include "powderbed/keff/hot_wall.hpp"
#include "powderbed/bed/psd.hpp"
#include "powderbed/bed/random.hpp"

namespace py = pybind11;
using namespace powderbed;

namespace {

py::dict read_bed(const std::string& path, std::optional<std::vector<double>> csv_bounds) {
  std::optional<bed::Domain> domain;
  if (csv_bounds) {
    if (csv_bounds->size() != 6) throw InputError("domain: 6 numbers xlo,ylo,zlo,xhi,yhi,zhi");
    const auto& b = *csv_bounds;
    domain.emplace();
    domain->lower = {b[0], b[1], b[2]};
    domain->upper = {b[3], b[4], b[5]};
    domain->dimension = (b[2] == 0 && b[5] == 0) ? 2 : 3;
    domain->validate("domain");
  }
  return python::bed_to_dict(bed::read_bed_any(path, domain ? &*domain : nullptr));
}

void write_bed(const py::dict& bed, const std::string& path) {
  bed::write_bed_any(python::bed_from_dict(bed), path);
}

// n radii drawn from the PSD string `spec` with the engine the programs use, seeded by `seed`.
py::array_t<double> sample_psd(const std::string& spec, std::size_t n, std::uint64_t seed) {
  const bed::Psd psd = bed::Psd::parse(spec, "psd");
  bed::Rng rng(seed);
  py::array_t<double> out(static_cast<py::ssize_t>(n));
  auto r = out.mutable_unchecked<1>();
  for (py::ssize_t i = 0; i < static_cast<py::ssize_t>(n); ++i) r(i) = psd.sample_radius(rng);
  return out;
}

// bedstat's JSON entry of one bed (bed/include/powderbed/bed/bed_report.hpp), as text for json.loads.
std::string stats_json(const py::dict& bed, double tol, std::optional<std::pair<double, double>> layer,
                       std::optional<std::string> psd, std::size_t profile, std::size_t rdf,
                       std::size_t histogram, bool voronoi, std::optional<double> order_margin,
                       const std::string& label) {
  bed::BedRequest req;
  req.tolerance = tol;
  req.layer = layer;
  if (psd) req.psd = bed::Psd::parse(*psd, "psd");
  req.profile_bins = profile;
  req.rdf_bins = rdf;
  req.histogram_bins = histogram;
  req.voronoi = voronoi;
  req.order_margin = order_margin;
  bed::Bed b = python::bed_from_dict(bed);
  b.validate(label);
  bed::JsonWriter json;
  bed::write_bed_json(json, bed::analyse_bed(std::move(b), label, req), req);
  return json.str();
}

// Whether `field` or a struct holding it ("phase_change" for "phase_change.melting_point") is in
// `given`.
bool field_given(const std::string& field, const std::set<std::string>& given) {
  for (auto dot = field.find('.'); dot != std::string::npos; dot = field.find('.', dot + 1))
    if (given.count(field.substr(0, dot))) return true;
  return given.count(field) > 0;
}

// material="NAME" of a run function: the (field, value) pairs the file `name` (a name of
// data/materials or a path, as --material takes it) gives `program`'s scene struct
// (bed/material_fills.hpp, the programs' own table), less the fields `given` beside it, which win
// as options given beside --material do; a required one neither gives is refused as the program
// refuses it. `temperature`: keff's bed temperature, where k_s is read.
py::list material_fills(const std::string& name, const std::string& program,
                        const std::set<std::string>& given, double temperature) {
  const bed::MaterialFile file = bed::read_named_material(name, "--material");
  py::list out;
  for (const bed::MaterialFill& fill : bed::kMaterialFills) {
    if (program != fill.program || field_given(fill.field, given)) continue;
    const auto value = bed::material_value(file, fill, temperature);
    if (!value && fill.required) bed::refuse_missing_fill(file, fill);
    if (!value) continue;
    out.append(py::make_tuple(fill.field, std::visit([](const auto& v) { return py::cast(v); }, *value)));
  }
  return out;
}

// keff's hot wall as the program keff holds it (keff/hot_wall.hpp): below the solidus of
// material="NAME" when one is named, else below tungsten's melting point unless trust_units.
void check_keff_hot_wall(const std::optional<std::string>& name, double hot_temperature,
                         bool trust_units) {
  if (!name) return keff::check_hot_wall(hot_temperature, nullptr, trust_units);
  const bed::MaterialFile file = bed::read_named_material(*name, "--material");
  keff::check_hot_wall(hot_temperature, &file, trust_units);
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "powderbed's C++ libraries (use the package powderbed, not this module)";
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError).attr("__doc__") =
      "Bad input (a value, a file, a keyword): the one line the programs print before exit 2.";
  py::register_exception<NumericalError>(m, "NumericalError", PyExc_ArithmeticError).attr("__doc__") =
      "A run that went non-finite (naming the particle or node and the step): the programs' exit 3.";
  m.def("read_bed", &read_bed, py::arg("path"), py::arg("domain") = py::none());
  m.def("write_bed", &write_bed, py::arg("bed"), py::arg("path"));
  m.def("sample_psd", &sample_psd, py::arg("spec"), py::arg("n"), py::arg("seed"));
  m.def("material_fills", &material_fills, py::arg("name"), py::arg("program"), py::arg("given"),
        py::arg("temperature"));
  m.def("check_keff_hot_wall", &check_keff_hot_wall, py::arg("name"), py::arg("hot_temperature"),
        py::arg("trust_units"));
  m.def("stats_json", &stats_json, py::arg("bed"), py::arg("tol"), py::arg("layer"),
        py::arg("psd"), py::arg("profile"), py::arg("rdf"), py::arg("histogram"),
        py::arg("voronoi"), py::arg("order_margin"), py::arg("label"));
  python::bind_dem_structs(m);
  python::bind_dem_runs(m);
  python::bind_keff(m);
  python::bind_thermal_structs(m);
  python::bind_sinter(m);
  python::bind_build(m);
  python::bind_packgen(m);
}
